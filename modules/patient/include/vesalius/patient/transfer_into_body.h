// The anatomy transfer after the skin registration (Dicko et al. 2013, §5, §7, §8, Fig. 2.b-f), as one pipeline:
// given where every reference skin vertex lands on the target's skin and the target's fat there,
//  1. erosion (§5, fat/erode_skin.h): the registered skin moved inwards by the fat thickness (none on the
//     reference's cut vertices, which are not skin);
//  2. sub-fat registration: the lean reference (§3: "warp our lean source anatomy to the sub-fat part of
//     the target") registered again, onto the eroded skin (transfer/articulated_registration.h, or plain
//     §4), as erosion takes the fat off along the normals only and the first registration's stretch
//     along the surface would carry into the bones (rule R3);
//  3. the reference's inside mask on a grid covering its skin and tissues, and the signed distances of
//     the eroded target body and the reference body with their cavities (meshing/body_distance.h, rules
//     R5, R6);
//  4. transfer::transferAnatomy (§7-8) into the eroded skin, the bones kept inside it.
// `vesalius transfer` runs its registration and then this; the virtual patient runs it after completing
// the reference into the patient (reference_completion.h).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/progress.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/transfer/anatomy_transfer.h"
#include "vesalius/transfer/articulated_registration.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

struct TransferIntoBodyOptions {
  // Step 2: articulated (parts given) or plain §4 registration with registration.registration.
  transfer::ArticulatedRegistrationOptions registration;
  bool articulated = true;
  double voxelSizeMm = 3;  // the displacement field's grid (step 3)
  // Step 4; its targetSkinDistance and referenceSkinDistance are set by the pipeline.
  transfer::AnatomyTransferOptions transfer;
};

struct TransferIntoBody {
  ReferenceAnatomy anatomy;        // the reference carried into the target: skin = the registered skin
  MatrixX3d erodedSkin;            // #skin V by 3: the sub-fat skin the tissues were carried into (Fig. 2.b)
  bool eroded = false;             // whether any fat was eroded (steps 1-2 ran)
  double erosionMeanMm = 0;        // fat::ErodedSkin's mean displacement, limited vertices, new self-intersections
  long erosionLimited = 0, erosionNewSelfIntersections = 0;
  double subFatMeanDistanceMm = 0, subFatScale = 1;  // step 2's registration
  GridGeometry grid;               // the field's grid
  meshing::BodyDistance erodedBody, referenceBody;  // step 3
  transfer::TransferredAnatomy transferred;         // step 4
  std::vector<std::pair<std::string, double>> stageSeconds;  // in the order they ran
};

// reference: the (lean) reference anatomy; registeredSkin: #skin V by 3, where each reference skin vertex
// lands on the target's skin (mm, LPS); fatThickness: #skin V, mm (0 on the cut); parts: the reference
// skin's parts for the articulated registration (transfer::skinPartsFromBones), unused when
// options.articulated is false. progress, if given, shows the transfer (step 4) as a stage.
// Throws BadInput on sizes that disagree with the reference skin, and as the steps do.
TransferIntoBody transferIntoBody(const ReferenceAnatomy& reference, const MatrixX3d& registeredSkin,
                                  const Eigen::VectorXd& fatThickness, const transfer::SkinParts& parts,
                                  const TransferIntoBodyOptions& options = {}, Progress* progress = nullptr);

}  // namespace vesalius::patient
