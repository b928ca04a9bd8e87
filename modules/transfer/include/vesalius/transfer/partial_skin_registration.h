// Registration of a whole source skin (a full-body reference) onto a partial target skin: a scan's body
// surface, closed by caps where its field of view cut the body (Dicko et al. 2013, §4's registration; its §2 notes
// that robustness to partial data comes from extrinsic, Cartesian correspondences, as here).
//
// Only skin pulls. The cut (the caps, ReferenceAnatomy::skinCutVertices) is where the scan stopped, not
// where the body does, so:
//  - forward pairs (a source vertex to its closest point on the target) whose target face touches a cut
//    vertex are dropped, and so are backward pairs from cut target vertices;
//  - a forward pair counts only if the source surface comes no nearer its target point than the source
//    vertex does, within reciprocalToleranceMm: the reference's arm hanging beside the patient's trunk,
//    which the scan does not show, has the trunk's skin as its closest target, but the reference's own
//    trunk lies nearer that skin.
// Method:
//  1. Alignment. The centroids of a full body and a torso piece say nothing of each other, so the
//     alignment starts from `alignmentStarts` heights along the body axis (S in LPS, the CT's and the
//     reference's long axis): at each, the target's centre is put at that height of the source and at the
//     centroid of the source's slab as tall as the target there; then alignIterations of similarity ICP
//     from the target's skin vertices to their closest points on the source (the partial side pulls the
//     whole, Besl and McKay 1992), pairs with incompatible normals or farther than three times their median
//     distance dropped (trimmed ICP, Chetverikov et al. 2002). Given bones both show (AlignmentBones), the
//     target's bone points pull the source's bones in the same fit, weighing as much as the skin: a trunk
//     is much the same tube at the waist and the chest, its pelvis is not. The refinedStarts starts whose
//     target skin (plus, given bones, bone points) ends nearest the source (mean distance) then run on
//     until they settle, and the nearest of them wins: unsettled, two starts bound for the same place can
//     score a few per cent apart in either order as rounding falls on one machine or another. Its
//     rotation is applied about the matched part of the source, its scale (the trunk's girth) only with
//     scaleSource.
//  2. Deformation: registerSkin's ICP with shape matching (skin_registration.h, steps 2-4) with the pairs
//     above. Vertices no pair reaches follow their clusters' shape matching there.
//  3. Continuation. The vertices a pair reached in the last iteration are the pulled ones: the skin the
//     scan sees. The others (the body beyond the field of view, and anything the scan does not show) are
//     replaced by a smooth continuation: the rigid transform S that best maps the pulled vertices' rest
//     positions to their registered ones, plus the pulled vertices' residual x − S(q) extended
//     harmonically over the skin's edge graph (surface_harmonic_extension.h) into the rest, so the
//     completed skin meets the registered part without a step and far away is the aligned reference
//     moved by S.
// Deviations, stated plainly: §4 registers whole skins; the cut handling, the reciprocal test, the multi-
// start alignment along S and the continuation are ours (docs/methods/skin-registration.md, "A partial
// target"). Beyond the field of view the body keeps the reference's size: a scan of the trunk says nothing
// of the patient's height, and a similarity fitted to a trunk scales the whole body, head and feet too, by
// its girth (the thin MakeHuman body's trunk makes the neutral 22% smaller, though it is 81 mm taller).
// The trunk's girth reaches beyond the cut through the harmonic residual, fading away from it.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/linalg/similarity_transform.h"
#include "vesalius/transfer/skin_registration.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::transfer {

struct PartialSkinRegistrationOptions {
  SkinRegistrationOptions registration;  // step 2; its align, alignIterations and landmarkWeight are unused
  int alignmentStarts = 12;              // heights tried in step 1, >= 1
  double startsFrom = 0.2, startsTo = 0.85;  // ... spread over this part of the source's height, from its foot
  int alignIterations = 20;              // similarity-ICP iterations at each start, >= 1
  int refinedStarts = 3;                 // the starts with the best scores then run on, >= 1,
  int refineIterations = 300;            // ... for at most this many iterations, >= 1,
  double settledMm = 0.01;               // ... until an iteration moves no matched point farther, > 0
  int alignmentPoints = 4000;            // step 1 pairs at most this many target points per side (evenly), >= 3
  double reciprocalToleranceMm = 10;     // forward pairs' reciprocal test, >= 0
  // Whether step 1 applies its similarity's scale to the source. Off: the source is only turned and moved
  // (about the part of it the target matched), keeping the reference's size; the deformation fits the
  // trunk's girth and the continuation carries it beyond the cut, fading.
  bool scaleSource = false;
};

// Bones both sides show, which anchor step 1 along the body (a trunk is much the same tube at the waist
// and the chest; its pelvis is not): the source's bone surfaces in the source skin's frame, and points on
// the target's bones (a CT's bone class or bone labels inside the field of view).
struct AlignmentBones {
  MatrixX3d sourceV;  // #Vb by 3
  MatrixX3i sourceF;  // #Fb by 3
  MatrixX3d target;   // #Pb by 3
};

struct PartialSkinRegistration {
  MatrixX3d V;                          // #Vs by 3: the completed skin (source topology), mm
  std::vector<char> pulled;             // #Vs: 1 where the target's skin pulled the vertex (step 3)
  // Step 1's transform of the source: x -> alignmentLinear x + alignmentTranslation.
  Eigen::Matrix3d alignmentLinear = Eigen::Matrix3d::Identity();
  Eigen::Vector3d alignmentTranslation = Eigen::Vector3d::Zero();
  double girthScale = 1;                // step 1's similarity scale: the trunk's girth against the source's
  SimilarityTransform continuation;  // step 3's S, rigid (maps the aligned source)
  double alignmentMeanDistance = 0;     // mean distance of the target's skin vertices to the source under
                                        // step 1's similarity, mm
  double skinMeanDistance = 0;          // mean and largest distance of the target's skin vertices (not cut)
  double skinMaxDistance = 0;           // to the completed skin, mm
};

// Vs: #Vs by 3, Fs: #Fs by 3 (the whole source skin); Vt: #Vt by 3, Ft: #Ft by 3 (the partial target with
// its caps); targetCutVertices: indices into Vt of the cut (not skin); bones: optional, for step 1. mm, LPS
// (S the body's long axis in both), triangles counter-clockwise seen from outside. Throws BadInput on an
// empty or broken mesh, a cut index out of range, a target with no skin vertex, or a target the source's
// skin never faces (fewer than 3 pairs); UsageError on impossible options. Deterministic: the result does
// not depend on the number of threads.
PartialSkinRegistration registerSkinToPartialTarget(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3d& Vt,
                                                    const MatrixX3i& Ft, const std::vector<int>& targetCutVertices,
                                                    const PartialSkinRegistrationOptions& options = {},
                                                    const AlignmentBones* bones = nullptr);

}  // namespace vesalius::transfer
