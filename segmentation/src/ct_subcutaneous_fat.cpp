// Stage 4 of the CT tissue classes: subcutaneous fat, the fat between the skin and the muscle wall
// (ct_tissues.h).
#include "ct_stages.h"

namespace vesalius::segmentation::detail {

Mask subcutaneousFat(const Mask& body, const Mask& fat, const Mask& interior, const CtTissueOptions& o) {
  // The dermis (thick on the back) is a soft-tissue sheet just under the skin, tied to the muscles by
  // septa; left in, it would make the fat layer a cavity of the wall. Below the shell, vessels and septa
  // in the fat are small islands, so the largest component is the wall with what it holds.
  const Mask wall = largestComponent(maskAndNot(interior, skinShell(body, o.muscleWallMinDepthMm)));
  // The closing bridges the gaps of the wall (linea alba, thin muscle at 3 mm voxels) through which
  // visceral fat would otherwise reach the outer layer.
  const Mask envelope =
      fillHolesSliceWise(largestComponent(closeMm(wall, o.muscleWallClosingMm)), axialAxis(body.geometry));
  return maskAndNot(fat, envelope);
}

}  // namespace vesalius::segmentation::detail
