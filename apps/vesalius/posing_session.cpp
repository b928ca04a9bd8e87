#include "posing_session.h"

#include "vesalius/core/error.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/text_file.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/corotational_fem.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/skeleton_pose.h"

#include <filesystem>
#include <iostream>

namespace vesalius::cli {

namespace {

// A foreign motion (+Y up) starts where the rig stands: its first frame is the stance. Our own
// skeleton.bvh (mm LPS) already holds the rig's positions and is replayed as written.
posing::RetargetOptions retargetOptions(bool motionLps, const Motion& motion) {
  posing::RetargetOptions options;
  if (motionLps) return options;
  options.sourceAxes = io::yUpToLps();
  if (motion.frameCount() > 0) options.sourceStance = motion.worldPose(0);
  return options;
}

}  // namespace

posing::JointMap motionJointMap(const std::string& mapPath, const Skeleton& source, const Skeleton& rig) {
  if (!mapPath.empty()) return posing::parseJointMap(io::readTextFile(mapPath), mapPath);
  posing::JointMap shared;
  for (const Joint& joint : rig.joints)
    if (source.find(joint.name) >= 0) shared.pairs.emplace_back(joint.name, joint.name);
  return shared.pairs.size() * 2 >= rig.joints.size() ? shared : posing::cmuToMakeHumanJointMap();
}

Motion readMotion(const std::string& bvhPath) {
  std::string warning;
  Motion motion = io::readBvh(bvhPath, &warning);
  if (!warning.empty()) std::cerr << "warning: " << warning << '\n';
  return motion;
}

RetargetedMotion::RetargetedMotion(const std::string& bvhPath, const std::string& mapPath, bool motionLps,
                                   const Skeleton& rig)
    : motion_(readMotion(bvhPath)),
      retargeter_(motion_.skeleton, rig, motionJointMap(mapPath, motion_.skeleton, rig), retargetOptions(motionLps, motion_),
                  mapPath.empty() ? "default joint map" : mapPath) {}

std::vector<Eigen::Isometry3d> RetargetedMotion::pose(int frame) const {
  return retargeter_.pose(motion_.worldPose(frame));
}

bool isSkinningMethod(const std::string& method) {
  return method == "lbs" || method == "dqs" || method == "cor" || method == "fem";
}

PosingSession::PosingSession(const std::string& anatomyDir, bool untangle, bool restoreVolume)
    : rig_(readAnatomyRig(anatomyDir)) {
  for (const std::string& path : rig_.meshes) {
    meshes_.push_back(io::readTriMesh(path));
    embeddings_.push_back(embedInTets(rig_.tets.V, rig_.tets.T, meshes_.back().V));
  }
  if (rig_.tets.vertexAttributes.real.count("cor_centre")) centres_ = rig_.centres();
  if (restoreVolume) restore_.emplace(rig_.tets.V, rig_.tets.T, rig_.boneOfVertex());
  if (untangle) untangle_.emplace(rig_.tets.V, rig_.tets.T, rig_.boneOfVertex());
}

int PosingSession::meshIndex(const std::string& stem) const {
  for (std::size_t m = 0; m < rig_.meshes.size(); ++m)
    if (std::filesystem::path(rig_.meshes[m]).stem() == stem) return int(m);
  return -1;
}

PosingSession::Repairs PosingSession::skinTets(const std::vector<Eigen::Isometry3d>& world,
                                              const std::string& method, MatrixX3d& tets) const {
  if (!isSkinningMethod(method)) throw UsageError("skinning method must be lbs, dqs, cor or fem, not " + method);
  const std::vector<Eigen::Isometry3d> all = posing::restToPosed(rig_.skeleton, world);
  std::vector<Eigen::Isometry3d> bones;
  for (int j : rig_.boneJoint) bones.push_back(all[j]);
  const MatrixX3d& V = rig_.tets.V;
  if (method == "lbs") {
    posing::linearBlendSkinning(V, rig_.weights(), bones, tets);
  } else if (method == "dqs") {
    posing::dualQuaternionSkinning(V, rig_.weights(), bones, tets);
  } else if (method == "cor") {
    if (centres_.rows() == 0) rig_.centres();  // throws the rig's BadInput: made without centres
    posing::corSkinning(V, rig_.weights(), centres_, bones, tets);
  } else {
    tets = posing::corotationalFem(V, rig_.tets.T, rig_.boneOfVertex(), bones).V;
  }
  Repairs repairs;
  if (restore_) repairs.restore = (*restore_)(tets);
  if (untangle_) repairs.untangle = (*untangle_)(tets);
  return repairs;
}

void PosingSession::carry(const MatrixX3d& tets, std::vector<MatrixX3d>& carried) const {
  carried.resize(embeddings_.size());
  for (std::size_t m = 0; m < embeddings_.size(); ++m) embeddings_[m].apply(tets, carried[m]);
}

}  // namespace vesalius::cli
