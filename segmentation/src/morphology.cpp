// Binary morphology with a Euclidean ball in mm, by thresholding distance maps (label_ops.h).
#include "vesalius/core/error.h"
#include "vesalius/segmentation/label_ops.h"

#include <cmath>

namespace vesalius::segmentation {
namespace {

// Distances come from sums of squared spacings, so a neighbour exactly on the sphere can land a rounding
// error either side of the radius; this tolerance keeps it inside the ball.
constexpr double kRadiusToleranceMm = 1e-3;

void requireRadius(double radiusMm) {
  if (!(radiusMm >= 0.0) || !std::isfinite(radiusMm))
    throw UsageError("morphology radius must be a finite number of mm >= 0");
}

Mask complement(const Mask& mask) {
  Mask out(mask.geometry);
  for (std::size_t n = 0; n < out.values.size(); ++n) out.values[n] = mask.values[n] == 0;
  return out;
}

}  // namespace

Mask dilateMm(const Mask& mask, double radiusMm) {
  requireRadius(radiusMm);
  const Grid<float> distance = distanceToMaskMm(mask);
  Mask out(mask.geometry);
  for (std::size_t n = 0; n < out.values.size(); ++n)
    out.values[n] = distance.values[n] <= radiusMm + kRadiusToleranceMm;
  return out;
}

Mask erodeMm(const Mask& mask, double radiusMm) {
  requireRadius(radiusMm);
  const Grid<float> distance = distanceToMaskMm(complement(mask));
  Mask out(mask.geometry);
  for (std::size_t n = 0; n < out.values.size(); ++n)
    out.values[n] = mask.values[n] && distance.values[n] > radiusMm + kRadiusToleranceMm;
  return out;
}

Mask openMm(const Mask& mask, double radiusMm) { return dilateMm(erodeMm(mask, radiusMm), radiusMm); }

Mask closeMm(const Mask& mask, double radiusMm) { return erodeMm(dilateMm(mask, radiusMm), radiusMm); }

}  // namespace vesalius::segmentation
