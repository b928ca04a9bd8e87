#include "vesalius/posing/rig_poser.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/corotational_fem.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/skeleton_pose.h"

#include <algorithm>
#include <filesystem>

namespace vesalius::posing {

bool isSkinningMethod(const std::string& method) {
  return method == "lbs" || method == "dqs" || method == "cor" || method == "fem";
}

RigPoser::RigPoser(AnatomyRig rig, std::vector<TriMesh> meshes, bool untangle, bool restoreVolume)
    : rig_(std::move(rig)), meshes_(std::move(meshes)) {
  if (meshes_.size() != rig_.meshes.size())
    throw UsageError("RigPoser: " + std::to_string(meshes_.size()) + " meshes for the rig's " +
                     std::to_string(rig_.meshes.size()) + " names");
  if (!rig_.meshJoint.empty() && rig_.meshJoint.size() != rig_.meshes.size())
    throw UsageError("RigPoser: " + std::to_string(rig_.meshJoint.size()) + " mesh joints for " +
                     std::to_string(rig_.meshes.size()) + " meshes");
  for (int j : rig_.meshJoint)
    if (j < -1 || j >= int(rig_.skeleton.joints.size())) throw UsageError("RigPoser: mesh joint " + std::to_string(j) + " out of range");
  for (const TriMesh& mesh : meshes_) embeddings_.push_back(embedInTets(rig_.tets.V, rig_.tets.T, mesh.V));
  if (rig_.hasCentres()) centres_ = rig_.centres();
  if (restoreVolume) restore_.emplace(rig_.tets.V, rig_.tets.T, rig_.boneOfVertex());
  if (untangle) untangle_.emplace(rig_.tets.V, rig_.tets.T, rig_.boneOfVertex());
}

int RigPoser::meshIndex(const std::string& stem) const {
  for (std::size_t m = 0; m < rig_.meshes.size(); ++m)
    if (std::filesystem::path(rig_.meshes[m]).stem() == stem) return int(m);
  return -1;
}

RigPoser::Repairs RigPoser::skinTets(const std::vector<Eigen::Isometry3d>& world, const std::string& method,
                                     MatrixX3d& tets) const {
  if (!isSkinningMethod(method)) throw UsageError("skinning method must be lbs, dqs, cor or fem, not " + method);
  const std::vector<Eigen::Isometry3d> all = restToPosed(rig_.skeleton, world);
  std::vector<Eigen::Isometry3d> bones;
  for (int j : rig_.boneJoint) bones.push_back(all[j]);
  const MatrixX3d& V = rig_.tets.V;
  if (method == "lbs") {
    linearBlendSkinning(V, rig_.weights(), bones, tets);
  } else if (method == "dqs") {
    dualQuaternionSkinning(V, rig_.weights(), bones, tets);
  } else if (method == "cor") {
    if (centres_.rows() == 0) rig_.centres();  // throws the rig's BadInput: made without centres
    corSkinning(V, rig_.weights(), centres_, bones, tets);
  } else {
    tets = corotationalFem(V, rig_.tets.T, rig_.boneOfVertex(), bones).V;
  }
  Repairs repairs;
  if (restore_) repairs.restore = (*restore_)(tets);
  if (untangle_) repairs.untangle = (*untangle_)(tets);
  // The repair's moves lose volume (a fold pushed out of a joint); give it back once, then repair what that
  // flattened.
  if (restore_ && untangle_ && repairs.untangle.movedVertices > 0) {
    const VolumeRestoreResult restore = (*restore_)(tets);
    const UntangleResult untangle = (*untangle_)(tets);
    repairs.restore.volumeChangeAfter = restore.volumeChangeAfter;
    repairs.restore.errorAfter = restore.errorAfter;
    repairs.restore.iterations += restore.iterations;
    repairs.restore.cgIterations += restore.cgIterations;
    repairs.restore.maxMove = std::max(repairs.restore.maxMove, restore.maxMove);
    repairs.restore.seconds += restore.seconds;
    repairs.untangle.badAfter = untangle.badAfter;
    repairs.untangle.regions += untangle.regions;
    repairs.untangle.movedVertices = std::max(repairs.untangle.movedVertices, untangle.movedVertices);
    repairs.untangle.maxMove = std::max(repairs.untangle.maxMove, untangle.maxMove);
    repairs.untangle.releasedBoneVertices += untangle.releasedBoneVertices;
    repairs.untangle.maxBoneMove = std::max(repairs.untangle.maxBoneMove, untangle.maxBoneMove);
    repairs.untangle.seconds += untangle.seconds;
  }
  return repairs;
}

void RigPoser::carry(const MatrixX3d& tets, const std::vector<Eigen::Isometry3d>& world,
                     std::vector<MatrixX3d>& carried) const {
  const std::vector<Eigen::Isometry3d> moved =
      rig_.meshJoint.empty() ? std::vector<Eigen::Isometry3d>{} : restToPosed(rig_.skeleton, world);
  carried.resize(embeddings_.size());
  for (std::size_t m = 0; m < embeddings_.size(); ++m) {
    const int j = rig_.jointOfMesh(m);
    if (j < 0) {
      embeddings_[m].apply(tets, carried[m]);
      continue;
    }
    const Eigen::Isometry3d& map = moved[std::size_t(j)];
    carried[m] = (meshes_[m].V * map.linear().transpose()).rowwise() + map.translation().transpose();
  }
}

}  // namespace vesalius::posing
