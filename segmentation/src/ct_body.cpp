// Stage 1 of the CT tissue classes: the body mask (ct_tissues.h).
#include "vesalius/core/error.h"
#include "vesalius/segmentation/ct_tissues.h"

#include <limits>
#include <string>

namespace vesalius::segmentation {

Mask segmentCtBody(const Image& ct, const CtTissueOptions& options) {
  const Mask dense = thresholdMask(ct, options.bodyMinHu, std::numeric_limits<float>::infinity());
  // The table and clothing touch the body only through bridges thinner than the opening ball.
  const Mask body = largestComponent(openMm(dense, options.bodyOpeningMm));
  if (countVoxels(body) == 0)
    throw BadInput("", "CT has no body: no voxel survives the threshold of " +
                           std::to_string(options.bodyMinHu) + " HU and the opening");
  return fillBodyHoles(body);
}

}  // namespace vesalius::segmentation
