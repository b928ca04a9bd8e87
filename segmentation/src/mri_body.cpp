// Stage 1 of the MRI tissue classes: the body mask (mri_tissues.h).
#include "mri_stages.h"
#include "vesalius/core/error.h"
#include "vesalius/segmentation/otsu.h"

#include <algorithm>
#include <limits>

namespace vesalius::segmentation {

Mask segmentMriBody(const Image& scan, const MriTissueOptions& options) {
  const auto [lo, hi] = std::minmax_element(scan.values.begin(), scan.values.end());
  if (lo == scan.values.end() || !(*lo < *hi)) throw BadInput("", "MRI is constant: no body to find");
  const Grid<float> smooth = detail::gaussianSmoothMm(scan, options.smoothingMm);
  const float level = options.bodyOtsuFraction * otsuThresholds(smooth).front();
  const Mask body =
      largestComponent(thresholdMask(smooth, level, std::numeric_limits<float>::infinity()));
  if (countVoxels(body) == 0) throw BadInput("", "MRI has no body: no voxel above the threshold");
  return fillBodyHoles(body);
}

}  // namespace vesalius::segmentation
