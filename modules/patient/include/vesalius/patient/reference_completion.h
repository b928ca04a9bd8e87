// The virtual patient outside the scan's field of view (docs/virtual-patient.md; Dicko et al. 2013, §3-8): the
// full-body reference (MakeHuman skin, OpenSim bones and muscle paths) completed into the patient.
//  1. The reference skin registered onto the patient's partial skin, where the scan sees skin only (the
//     field of view's cut pulls nothing), and continued smoothly beyond it
//     (transfer/partial_skin_registration.h): the completed skin, reference topology. Its alignment along
//     the body is anchored by the bones: the patient's bone tissues (the CT's bone class, or its bone
//     labels) against the reference's bones.
//  2. The fat at every completed skin vertex: inside the field of view the patient's (fat forests, §5),
//     carried from the closest point of the patient's skin (barycentric over its triangle); beyond it the
//     same extended harmonically over the skin (transfer/surface_harmonic_extension.h), as the body
//     beyond the scan is continued.
//  3. The reference transferred into the completed skin (transfer_into_body.h: erosion §5, sub-fat
//     registration, interpolation §7, bone registration §8).
//  4. What the transfer left outside the completed skin (a foot bone's tip where the skin is thin) bent
//     inside by one smooth displacement of all tissues (transfer/bones_warped_into_skin.h), so that tissues
//     side by side stay so (Dicko et al. 2013, §3, rules R5, R6).
// Deviations, plainly: Dicko et al. 2013 completes its torso reference with a full body before transfer; here the
// patient's own scan is partial and the full body is fitted to it, so beyond the field of view the body
// is the reference's, with the trunk's girth and pose (partial_skin_registration.h). Organ labels play no
// part beyond their bones' surfaces in the alignment.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/progress.h"
#include "vesalius/patient/transfer_into_body.h"
#include "vesalius/transfer/partial_skin_registration.h"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace vesalius::patient {

struct ReferenceCompletionOptions {
  transfer::PartialSkinRegistrationOptions registration;  // step 1
  bool alignBones = true;  // step 1's alignment also pulls the reference's bones onto the patient's bone tissues
  // Step 3, with a 4 mm field: on the shipped CT a 3 mm field took 102 s and 7.2 GB for the same skin
  // (0.71 against 0.73 mm mean) and bones (none outside), 4 mm 56 s and 3.5 GB, as the full body with its
  // arms spread makes a large grid.
  TransferIntoBodyOptions transfer = withFieldVoxel(4.0);
  transfer::InsideSkinWarpOptions intoSkin;  // step 4

  static TransferIntoBodyOptions withFieldVoxel(double mm) {
    TransferIntoBodyOptions o;
    o.voxelSizeMm = mm;
    return o;
  }
};

struct ReferenceCompletion {
  ReferenceAnatomy anatomy;       // the full-body reference in the patient: skin = the completed skin
  std::vector<char> pulled;       // #reference skin V: 1 where the patient's skin pulled the vertex
  Eigen::VectorXd fatThickness;   // #reference skin V: the fat of step 2, mm
  MatrixX3d erodedSkin;           // #reference skin V by 3: the sub-fat skin the tissues were carried into
  transfer::PartialSkinRegistration registration;  // step 1 (its V is anatomy.skin.V)
  TransferIntoBody transfer;      // step 3's details (its anatomy before step 4)
  // Step 4: tissue vertices outside the completed skin before and after it, and its largest move (mm).
  long outsideBefore = 0, outsideAfter = 0;
  double bendLargestMm = 0;
  std::vector<std::pair<std::string, double>> stageSeconds;  // in the order they ran
};

// patientInFov: the patient's anatomy inside the field of view (scanAnatomy / buildVirtualPatient): its
// skin, mm LPS, with skinCutVertices marking the field of view's cut; its bone tissues anchor the
// alignment (none: the skin alone aligns).
// fatThickness: #patient skin V, mm. fullBodyReference: the full-body reference (`vesalius reference
// full-body`'s folder, io::readReferenceAnatomy), mm LPS. Throws BadInput if the sizes disagree, and as the steps do.
ReferenceCompletion completeWithReference(const ReferenceAnatomy& patientInFov, const Eigen::VectorXd& fatThickness,
                                          const ReferenceAnatomy& fullBodyReference,
                                          const ReferenceCompletionOptions& options = {}, Progress* progress = nullptr);

}  // namespace vesalius::patient
