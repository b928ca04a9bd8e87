// A mask edit of labels put back into their label map: what `vesalius labels components`, `fill` and
// `morph` run. Each label of `ids`, in the order given, is replaced by the edit of its mask (label_ops.h:
// the largest 26-connected component, components of at least a volume, holes filled in 3D or per axial
// slice, or a ball of radiusMm dilating, eroding, opening or closing it). Voxels the label loses become
// background; voxels it gains are taken from the background only, unless `overwrite` lets it take them
// from other labels too (then a label edited later may take voxels from one edited before it). The table
// is kept as it is.
#pragma once

#include "vesalius/core/label_map.h"

#include <vector>

namespace vesalius::segmentation {

enum class MaskEdit { LargestComponent, DropSmallComponents, FillHoles, FillHolesAxial, Dilate, Erode, Open, Close };

struct LabelMaskEditOptions {
  MaskEdit edit = MaskEdit::LargestComponent;
  double minMl = 0;         // DropSmallComponents: components below this volume (mL) go, rounded up to voxels
  double radiusMm = 0;      // Dilate, Erode, Open, Close: the ball's radius (voxel centres within it)
  bool overwrite = false;   // gained voxels may come from other labels, not only from the background
};

// map: the label map; ids: labels of it, each at most once. Returns the edited map. Throws UsageError for a
// negative or non-finite minMl, or a radius that is not positive and finite where the edit needs one.
LabelMap editLabelMasks(const LabelMap& map, const std::vector<Label>& ids, const LabelMaskEditOptions& options);

}  // namespace vesalius::segmentation
