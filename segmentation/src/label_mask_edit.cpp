// Mask edits of labels put back into their map (label_mask_edit.h).
#include "vesalius/segmentation/label_mask_edit.h"

#include "vesalius/core/error.h"
#include "vesalius/segmentation/label_ops.h"

#include <cmath>
#include <cstdint>

namespace vesalius::segmentation {
namespace {

Mask edited(const Mask& mask, const LabelMaskEditOptions& o, std::int64_t minVoxels, int axis) {
  switch (o.edit) {
    case MaskEdit::LargestComponent: return largestComponent(mask);
    case MaskEdit::DropSmallComponents: return removeSmallComponents(mask, minVoxels);
    case MaskEdit::FillHoles: return fillHoles3d(mask);
    case MaskEdit::FillHolesAxial: return fillHolesSliceWise(mask, axis);
    case MaskEdit::Dilate: return dilateMm(mask, o.radiusMm);
    case MaskEdit::Erode: return erodeMm(mask, o.radiusMm);
    case MaskEdit::Open: return openMm(mask, o.radiusMm);
    case MaskEdit::Close: return closeMm(mask, o.radiusMm);
  }
  throw UsageError("label mask edit: unknown edit");
}

bool needsRadius(MaskEdit e) {
  return e == MaskEdit::Dilate || e == MaskEdit::Erode || e == MaskEdit::Open || e == MaskEdit::Close;
}

}  // namespace

LabelMap editLabelMasks(const LabelMap& map, const std::vector<Label>& ids, const LabelMaskEditOptions& o) {
  if (!(o.minMl >= 0) || !std::isfinite(o.minMl)) throw UsageError("label mask edit: the volume must be >= 0 mL");
  if (needsRadius(o.edit) && (!(o.radiusMm > 0) || !std::isfinite(o.radiusMm)))
    throw UsageError("label mask edit: the radius must be a number of mm > 0");
  const double voxelMl = map.labels.geometry.spacing.prod() / 1000.0;
  const auto minVoxels = std::int64_t(std::ceil(o.minMl / voxelMl - 1e-9));
  const int axis = o.edit == MaskEdit::FillHolesAxial ? axialAxis(map.labels.geometry) : 2;
  LabelMap out = map;
  for (Label id : ids) {
    const Mask before = maskOf(out.labels, id);
    const Mask after = edited(before, o, minVoxels, axis);
    Mask gained = maskAndNot(after, before);
    if (!o.overwrite) gained = maskAnd(gained, maskOf(out.labels, 0));
    paintMask(out.labels, maskAndNot(before, after), 0);
    paintMask(out.labels, gained, id);
  }
  return out;
}

}  // namespace vesalius::segmentation
