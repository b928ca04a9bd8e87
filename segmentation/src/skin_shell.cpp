// The skin shell of a body mask (skin_shell.h): stage 2 of the CT and MRI tissue classes.
#include "skin_shell.h"

namespace vesalius::segmentation::detail {

Mask skinShell(const Mask& body, double thicknessMm) {
  Mask outside(body.geometry);
  for (std::size_t n = 0; n < body.values.size(); ++n) outside.values[n] = body.values[n] == 0;
  // Depth of a body voxel centre below the surface: the distance to the nearest outside voxel centre,
  // less the half voxel between the outermost centres and the surface they sample.
  const Grid<float> toOutside = distanceToMaskMm(outside);
  const double halfVoxel = 0.5 * body.geometry.spacing.minCoeff();
  Mask skin(body.geometry);
  for (std::size_t n = 0; n < body.values.size(); ++n)
    skin.values[n] = body.values[n] && toOutside.values[n] - halfVoxel < thicknessMm;
  return skin;
}

}  // namespace vesalius::segmentation::detail
