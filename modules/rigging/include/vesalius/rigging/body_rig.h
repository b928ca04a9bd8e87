// The posing rig of a body (Sujar et al. 2018, §3.1-3.5 preprocessing): a tet mesh of the inside of the skin with
// bone regions, bone weights (§3.3) and centres of rotation (§3.5), from one of three inputs:
//  - a skin and a skeleton: the inside of the skin voxelized (bone_mesh_labels.h) and tetrahedralized within
//    2x of the tet target (meshing/tet_budget.h), the bones capsules around the skeleton's segments
//    (posing/bone_capsules.h), each capsule inside the tets holding a vertex and no tet of bone vertices
//    alone joining two bones (docs/methods/posing.md);
//  - a label map with segmented bones (a CT's TotalSegmentator labels): the skeleton from the labels
//    (posing/skeleton_from_bones.h), the body and its bones as nested region surfaces (label_regions.h);
//  - a reference anatomy with OpenSim's bone meshes in its skin: the skeleton from the meshes
//    (posing/skeleton_from_bone_meshes.h), the bone regions from the meshes voxelized (bone_mesh_labels.h).
// `vesalius rig` runs them on files; `vesalius patient` rigs a patient's model through rigFromBoneLabels.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/posing/bone_capsules.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"
#include "vesalius/posing/skeleton_from_bones.h"

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::rigging {

struct RigOptions {
  // Voxels of the inside image (skin, reference), or of the labels meshed (labels; coarser only), mm;
  // grown if needed to keep the image under Sujar et al.'s 250x120x700 voxels (§3.2).
  double voxelSize = 4.0;
  double margin = 15.0;      // labels: only the bones' box grown by this is meshed, mm
  long targetTets = 100000;  // about this many tets
  bool corCentres = true;    // compute the centres of rotation that CoR skinning needs (a few seconds)
  posing::BoneCapsuleOptions capsules;  // skin and skeleton: the bone capsules
};

struct BuiltRig {
  AnatomyRig rig;  // its `meshes` left empty: the caller names what the rig carries
  // The surfaces the rig's regions were made of, named by file: "skin.vtp" for the body, "<label>.vtp" per
  // bone label (labels only; empty otherwise).
  std::vector<std::pair<std::string, TriMesh>> regionSurfaces;
  std::vector<std::pair<std::string, double>> stageSeconds;  // in the order they ran
  // Reference only: its bone tissues by name and the joint each moves with; a carried mesh of that name is
  // a bone mesh (meshJoints), moved rigidly. The bone regions are those meshes voxelized, coarser than
  // them, so the tets would bend them. A rig of bone labels has none: its regions are its labels, and its
  // meshes follow the tets as the re-posed scan does, so the two agree.
  std::map<std::string, int> boneJoints;
  double femoralHeadRadiusLeft = NAN, femoralHeadRadiusRight = NAN;  // mm (labels, reference)
};

// skin: closed, mm LPS; skeleton: mm LPS. Throws BadInput naming `source` (the skin's file) for an open or
// empty skin, and `skeletonSource` for a skeleton none of whose bones lies inside the skin.
BuiltRig rigFromSkeleton(const TriMesh& skin, const Skeleton& skeleton, const RigOptions& options,
                         const std::string& source, const std::string& skeletonSource, Progress* progress = nullptr);

// labels: a map with the bones that posing::skeletonFromBones names (hips, sacrum, femurs, lumbar
// vertebrae); the body is every labelled voxel made solid (closed, holes filled, its largest part), so a
// map whose body voxels carry a label of their own gives that body. Throws what skeletonFromBones and the
// tet mesher throw, naming `source`.
BuiltRig rigFromBoneLabels(const LabelMap& labels, const posing::SkeletonFromBonesOptions& bones,
                           const RigOptions& options, const std::string& source, Progress* progress = nullptr);

// reference: OpenSim's bone meshes (tissues grouped by OpenSim body) in a closed skin, mm LPS. Bones of
// the torso's joint that `bones` does not name (a patient's labelled vertebrae and ribs in a virtual
// patient's model) join its torso, spine and scapulae; names it holds no mesh of are left out.
BuiltRig rigFromReference(const ReferenceAnatomy& reference, const posing::SkeletonFromBoneMeshesOptions& bones,
                          const RigOptions& options, const std::string& source, Progress* progress = nullptr);

// Throws UsageError, naming the least target, when targetTets is below the smallest that a rig of `bones`
// bone labels keeps within twice (rigging::leastTargetTets): rigFromBoneLabels (reference false: the body
// every labelled voxel) and rigFromReference (reference true: one label per joint with bone voxels, in a
// skin that keeps more triangles) check it before their surfaces are made.
void checkRigTargetTets(long targetTets, std::size_t bones, bool reference);

// meshes: file names (AnatomyRig::meshes). Returns AnatomyRig::meshJoint for them: the joint of the bone
// named by a file's stem in boneJoints, -1 for every other mesh.
std::vector<int> meshJoints(const std::vector<std::string>& meshes, const std::map<std::string, int>& boneJoints);

}  // namespace vesalius::rigging
