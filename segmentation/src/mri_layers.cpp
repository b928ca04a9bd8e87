// Stages 3-5 of the MRI tissue classes: the bright fat layer and the dark bone layer under the skin
// (mri_tissues.h).
#include "skin_shell.h"
#include "mri_stages.h"
#include "vesalius/segmentation/otsu.h"

#include <cmath>
#include <limits>

namespace vesalius::segmentation::detail {

MriLayers mriLayers(const Image& scan, const Mask& body, const Mask& skin, const MriTissueOptions& o) {
  // The band under the skin holds the scalp (fat, muscle) and the outer skull and CSF, so its histogram
  // has the three modes the thresholds split. Over the whole body the brain would swamp them: on the head
  // MRI the upper level would fall between grey and white matter, and fat would grow from the eyelids
  // through the orbits to the brain.
  const Mask inner = maskAndNot(body, skin);
  const Mask band = maskAndNot(skinShell(body, o.layerDepthMm), skin);
  const std::vector<float> levels = otsuThresholds(scan, &band, OtsuOptions{3, 256});
  const float inf = std::numeric_limits<float>::infinity();

  MriLayers layers;
  const Mask bright = maskAnd(band, thresholdMask(scan, levels[1], inf));
  layers.fat = maskAndNot(componentsTouching(maskOr(bright, skin), skin), skin);

  // Bone is dark and lies under the scalp; the distance limit keeps out the CSF of deep sulci and the
  // ventricles, which are as dark but connected to the skull through the CSF under it.
  const Grid<float> fromScalp = distanceToMaskMm(maskOr(skin, layers.fat));
  Mask dark = maskAndNot(inner, layers.fat);
  Mask seeds(body.geometry);
  for (std::size_t n = 0; n < dark.values.size(); ++n) {
    dark.values[n] = dark.values[n] && scan.values[n] < levels[0] &&
                     fromScalp.values[n] <= o.maxBoneDistanceMm;
    seeds.values[n] = dark.values[n] && fromScalp.values[n] <= o.boneSeedDistanceMm;
  }
  // Dark specks (vessels, partial volume at air pockets) are not bone.
  const double voxelMl = scan.geometry.spacing.prod() / 1000.0;
  layers.bone = removeSmallComponents(componentsTouching(dark, seeds),
                                      static_cast<std::int64_t>(std::ceil(o.minBoneComponentMl / voxelMl)));
  return layers;
}

}  // namespace vesalius::segmentation::detail
