// Stage 4 of the CT tissue classes: subcutaneous fat, the fat between the skin and the muscle wall
// (ct_tissues.h).
#include "ct_stages.h"

namespace vesalius::segmentation::detail {

Mask subcutaneousFat(const Mask& fat, const Mask& skin, const Mask& interior, double closingMm) {
  // Vessels and septa inside the fat layer are small islands of the interior; only the main body of
  // muscle, organs and bone shapes the wall. The closing bridges the gaps of the wall (linea alba, thin
  // muscle at 3 mm voxels) through which visceral fat would otherwise reach the skin.
  Mask envelope = largestComponent(closeMm(largestComponent(interior), closingMm));
  envelope = fillHolesSliceWise(envelope, axialAxis(fat.geometry));
  const Mask outerFat = maskAndNot(fat, envelope);
  // Fat in the outer layer that is cut off from the skin (between muscles of the limbs) is not
  // subcutaneous.
  return maskAnd(componentsTouching(maskOr(outerFat, skin), skin), outerFat);
}

}  // namespace vesalius::segmentation::detail
