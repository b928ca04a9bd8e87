// Label bounding boxes found in one pass, and the surface of a label inside its box (internal to meshing).
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/meshing/label_surface.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace vesalius::meshing::detail {

struct LabelBox {
  Eigen::Vector3i lo, hi;  // inclusive voxel index bounds; lo > hi when the label has no voxels
  std::int64_t voxels = 0;
};

// One box per label value 0..max label present (index = label id), from a single scan of the grid;
// background (0) gets none (voxels 0).
std::vector<LabelBox> labelBoxes(const Grid<Label>& labels);

// The surface of label `id`, whose voxels all lie in `box` (box.voxels > 0); see labelSurface.
// Throws UsageError on bad options.
TriMesh labelSurfaceInBox(const LabelMap& labels, Label id, const LabelBox& box, const SurfaceOptions& options);

}  // namespace vesalius::meshing::detail
