// Stage 3 of the CT tissue classes: bone (ct_tissues.h).
#include "ct_stages.h"

#include <cmath>
#include <limits>

namespace vesalius::segmentation::detail {

Mask ctBone(const Image& ct, const Mask& body, const CtTissueOptions& options) {
  Mask bone = maskAnd(body, thresholdMask(ct, options.boneMinHu, std::numeric_limits<float>::infinity()));
  // Thin cortex breaks up at 3 mm voxels; closing reconnects it so that the marrow (trabecular bone,
  // often below the threshold, fatty marrow even in the fat range) becomes a hole the fill can close.
  bone = maskAnd(body, closeMm(bone, options.boneClosingMm));
  for (int axis = 0; axis < 3; ++axis) bone = fillHolesSliceWise(bone, axis, options.maxMarrowAreaMm2);
  const double voxelMl = ct.geometry.spacing.prod() / 1000.0;
  const auto minVoxels = static_cast<std::int64_t>(std::ceil(options.minBoneComponentMl / voxelMl));
  return removeSmallComponents(bone, minVoxels);
}

}  // namespace vesalius::segmentation::detail
