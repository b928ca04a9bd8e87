// Anatomy transfer (Dicko et al. 2013, §7–8, Fig. 2.d–f): a reference anatomy carried into a target body, given
// where every reference skin vertex lands in the target (skin registration §4, then erosion §5).
//
//   1. Interpolation (§7): the skin displacement, fixed on the skin, is extended harmonically into the
//      reference body (displacement_field.h). Cut skin vertices (ReferenceAnatomy::skinCutVertices, where
//      a scan's field of view cut the body) fix nothing: the body goes on beyond them.
//   2. Bone registration (§8): each bone group moves by the affine map that best fits its interpolated
//      position (bone_registration.h), from its vertices at least a cell deep inside the reference skin
//      (all of them if fewer than 4 are), as the field is extrapolated only a few cells beyond the skin;
//      symmetric groups (the trunk) by maps symmetric about the sagittal
//      plane, the target's plane being the image of the reference's under the trunk's joint affine fit;
//      groups of long bones only (isLongBone, anatomy_checks.h) by a rotation and two scales, along the
//      bone and across it, the one across no larger, as the muscle around a limb does not widen its
//      bones (bone_registration.h).
//      Given the target's eroded skin as a signed distance, the fit is reweighted so that the bones stay
//      inside it (rule R6): the springs of vertices the map puts outside, or within a margin, grow stiffer.
//      What no affine map of the group brings inside is then bent inside (bones_warped_into_skin.h):
//      Dicko et al. 2013 leaves collisions to "standard collision handling routines" (§8); a bend local to the
//      vertices still outside, which leaves the rest of the bone on its map. A vertex goes as deep as it
//      was in the reference, at most the margin; one outside the reference's own skin stays.
//   3. Final interpolation (§7, Fig. 2.e): a second field fixed on the skin and on the registered bones;
//      every other tissue and every point not on a bone moves by it. Bone vertices less than a cell deep
//      inside the reference skin do not fix the field: there the skin's value wins, as two fixed shells
//      a cell apart with different values fold the field between them; for the same reason neither do
//      bone vertices within two cells of another group's bone, where the two groups' maps meet at a joint.
//      Bones and the points fixed to them move by their affine maps, and bends, exactly (rules R1, R7).
// The grid is the caller's (it covers the reference skin and every tissue), with the reference body's
// inside mask on it; the field runs in reference space, as Dicko et al.'s.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/transfer/bone_registration.h"
#include "vesalius/transfer/bones_warped_into_skin.h"
#include "vesalius/transfer/displacement_field.h"

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace vesalius::transfer {

struct AnatomyTransferOptions {
  DisplacementFieldOptions field;
  // Rule R6 in step 2: the signed distance (mm, negative inside) to the target's eroded skin on a grid in
  // target space (the caller's, not copied). Without it the maps are the plain least-squares fits.
  const Grid<float>* targetSkinDistance = nullptr;
  // The signed distance to the reference's own skin (reference space): a bone vertex the reference has
  // outside it is the reference's, not the transfer's, and is not bent; the others are bent at most as deep
  // as they were in the reference. Without it every vertex outside is bent in.
  const Grid<float>* referenceSkinDistance = nullptr;
  double insideMarginMm = 2.0;     // how deep inside a bone vertex is wanted, if its attractor is as deep
  double insideWeightGrowth = 2.0; // a shallower vertex's spring is stiffened by this factor per pass
  double insideMaxWeight = 1024;   // up to this stiffness (the others' is 1)
  int insidePasses = 100;          // at most this many fits
  // Step 3: bone vertices within this many cells of another group's bone fix nothing in the final field
  // (where two groups' maps meet at a joint; rowsAtJoints in anatomy_transfer.cpp).
  int jointFreeCells = 2;
  // Step 3: the final field's fixed cells at or beside a fold are freed and the field solved again, up to
  // this many times (DisplacementFieldOptions::unfoldPasses; the skin field, which moves no tissue, keeps
  // field.unfoldPasses).
  int finalUnfoldPasses = 40;
  // Step 2 with a target for some bone groups (§8's per-bone registration with a patient's segmented bone
  // as the target, as the virtual patient's bone labels give inside a scan's field of view): group name →
  // #P by 3 points on that group's bones in the target. Such a group's map, in its class (symmetric, long
  // bone or affine), is refined from the fit to its attractors by ICP (Besl and McKay 1992): each point
  // pairs with the closest point of the mapped group, and the map is fitted again to those pairs and, with
  // `boneTargetAttractorShare` of the points' weight in all, to its attractors, which hold what the points
  // leave undetermined (a femur cut by the field of view keeps its length). The final field (step 3) then
  // carries every other tissue with the bones where the target put them.
  std::map<std::string, MatrixX3d> boneTargets;
  double boneTargetAttractorShare = 0.1;
  int boneTargetIterations = 30;
};

struct BoneGroupMap {
  std::string group;          // the tissues' group, or the tissue's name for a bone of its own
  std::vector<int> tissues;   // indices into ReferenceAnatomy::tissues
  bool symmetric = false;
  bool longBones = false;     // not symmetric, and every tissue a long bone (isLongBone): fitLongBoneMap
  AffineMap map;
  InsideSkinWarp bend;          // after the map: what it leaves outside the eroded skin, bent inside (step 2)
  double rmsToAttractorMm = 0;  // RMS distance of the mapped bone to its interpolated position
  // With a target (AnatomyTransferOptions::boneTargets): the target points' RMS distance to the mapped
  // group before and after the ICP, mm; NaN without one.
  double targetRmsBeforeMm = std::numeric_limits<double>::quiet_NaN();
  double targetRmsAfterMm = std::numeric_limits<double>::quiet_NaN();
  MatrixX3d place(const MatrixX3d& rest) const { return bend.apply(map.apply(rest)); }  // #P by 3 → #P by 3
};

struct TransferredAnatomy {
  std::vector<MatrixX3d> tissues;      // per reference tissue: its vertices in the target (same rows)
  std::vector<MatrixX3d> interpolated; // per tissue: after step 1 only (Dicko et al.'s Fig. 4, left)
  MatrixX3d points;                    // per reference point
  std::vector<BoneGroupMap> boneGroups;
  Plane sagittal;                      // the target's sagittal plane
  DisplacementField skinField, finalField;
  double secondsSkinField = 0, secondsBones = 0, secondsFinalField = 0;
};

// targetSkin: #skin V by 3, where each reference skin vertex lands. referenceInside: the reference skin's
// inside mask on the field's grid. Throws BadInput if targetSkin's rows differ from the skin's, a mesh or
// point lies off the grid, or a value is not finite.
TransferredAnatomy transferAnatomy(const ReferenceAnatomy& reference, const MatrixX3d& targetSkin,
                                   const Grid<std::uint8_t>& referenceInside,
                                   const AnatomyTransferOptions& options = {});

}  // namespace vesalius::transfer
