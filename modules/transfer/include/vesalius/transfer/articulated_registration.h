// Skin registration with an articulated stage (Dicko et al. 2013, §4, extended): the reference skin is cut into
// parts by its bones, each limb part turned about its joint onto the target in chain order, the parts'
// transforms blended by smooth skin weights (linear blend skinning), and only then is the skin deformed
// by §4's ICP with shape matching (skin_registration.h).
//
// Why: §4's ICP pulls every vertex to its closest point and lets shape matching spread the motion along
// the surface. Where the target holds a limb at another angle (MakeHuman's thin body, 81 mm taller than the
// neutral, holds its hands further out and forward), closest points on a limb's sides slide the skin
// along the limb instead of turning it: the neutral's hand skin landed 60 mm (mean) from its true place on
// the thin body. Turning the limb's parts first removes that error before the closest points decide.
//
// The stages:
//  1. Similarity alignment of the whole skin (skin_registration.h, step 1).
//  2. Parts (skinPartsFromBones): every skin vertex belongs to the bone group whose bone mesh is closest;
//     symmetric (trunk) groups together form the trunk, part 0; parts touching along skin edges form a
//     tree rooted at the trunk (breadth first; a part's parent is its neighbour one level up with the
//     longest shared border), and a part's joint is the mean of the midpoints of that border's edges.
//     Parts with the same parent that share a border (the skin over radius and ulna, over patella and
//     tibia, over talus and calcaneus) are merged into one: they are one segment of the limb.
//  3. Articulation, in passes: each pass takes fresh correspondences of the whole skin (those of
//     skin_registration.h's step 2), then fits the parts in order, parents before children, each from the
//     pairs' current source points: the trunk by a rigid transform fitted to its own vertices' pairs (it
//     keeps step 1's scale: a trunk's girth is not the body's height), every other part by a rotation and
//     a scale about its joint, as its parent has placed it, fitted to the pairs of its whole subtree (a
//     forearm turns with its hand), which moves the subtree along. The fit about a fixed point is
//     Kabsch's (Arun et al. 1987) with both point sets centred on the joint, and the scale Umeyama's.
//  4. Blending: weights one-hot per part, smoothed blendIterations times by averaging each vertex's with
//     its skin neighbours'; the articulated skin is Σ_p w_vp T_p(x_v) (linear blend skinning).
//  5. §4's ICP with shape matching from the articulated skin, with it as the rest shape (no second
//     alignment).
// Deviations from Dicko et al. 2013, stated plainly: §4 has no articulated stage; its characters are registered by
// ICP and shape matching alone (with manual landmarks where that fails). The parts come from the
// reference's bones, not from a rig: no skin weights are needed beyond the skin and the bones. Limb parts
// scale about their joints because limbs differ in length between people (the thin body's hand is
// larger than the neutral's); a scale is isotropic, so it also thickens the part, which step 5 corrects.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/mesh.h"
#include "vesalius/linalg/similarity_transform.h"
#include "vesalius/transfer/skin_registration.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vesalius::transfer {

struct SkinParts {
  std::vector<int> partOfVertex;       // #skin V: the part of each vertex
  std::vector<std::string> names;      // per part: "trunk" (part 0) or the free bone group's name
  std::vector<int> parent;             // per part: its parent, -1 for the trunk and parts not joined to it
  std::vector<Eigen::Vector3d> joint;  // per part: the mean midpoint of its border with the parent, mm
  std::vector<int> order;              // the trunk and the parts joined to it, parents before children
};

// The reference skin cut by its bones (step 2). Bones with an empty group are parts of their own.
// A reference without bones gives one part, the trunk.
SkinParts skinPartsFromBones(const ReferenceAnatomy& reference);

struct ArticulatedRegistrationOptions {
  SkinRegistrationOptions registration;  // steps 1 and 5
  int passes = 40;                       // passes of step 3, >= 0 (0: no articulation)
  bool partScale = true;                 // let each limb part scale about its joint (false: rotation only)
  int blendIterations = 10;              // smoothing passes of the skin weights, >= 0
};

struct ArticulatedRegistration {
  SkinRegistration registration;                       // alignment is step 1's
  MatrixX3d articulated;                               // #V by 3: the skin after step 4, mm
  std::vector<SimilarityTransform> partTransforms;  // per part, acting on the aligned skin
};

// Vs, Fs: the reference skin (parts.partOfVertex has a row per vertex); Vt, Ft: the target skin; mm, LPS.
// landmarks: manual correspondences, used by the alignment (step 1) and the deformation (step 5) as
// registerSkin uses them. Throws as registerSkin does, and BadInput when parts does not fit Vs; UsageError
// on impossible options.
ArticulatedRegistration registerSkinArticulated(const MatrixX3d& Vs, const MatrixX3i& Fs, const SkinParts& parts,
                                                const MatrixX3d& Vt, const MatrixX3i& Ft,
                                                const ArticulatedRegistrationOptions& options = {},
                                                const std::vector<SkinLandmark>& landmarks = {});

}  // namespace vesalius::transfer
