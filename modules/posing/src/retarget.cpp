#include "vesalius/posing/retarget.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <limits>

namespace vesalius::posing {
namespace {

// Direction of joint j's bone in its own frame: to its tail, else to its only child; zero if neither.
Eigen::Vector3d boneDirection(const Skeleton& skeleton, int j) {
  if (skeleton.joints[j].tail.norm() > 0) return skeleton.joints[j].tail;
  int children = 0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  for (const Joint& joint : skeleton.joints)
    if (joint.parent == j) {
      ++children;
      offset = joint.restLocal.translation();
    }
  return children == 1 ? offset : Eigen::Vector3d::Zero();
}

// Height of the lowest joint along `up` in a pose.
double lowestJoint(const std::vector<Eigen::Isometry3d>& pose, const Eigen::Vector3d& up) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Isometry3d& joint : pose) lowest = std::min(lowest, joint.translation().dot(up));
  return lowest;
}

// Height of the roots above the lowest joint along `up` in a pose (all roots: a BVH has one).
double hipHeight(const std::vector<Eigen::Isometry3d>& pose, const Skeleton& skeleton, const Eigen::Vector3d& up) {
  double root = -std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < pose.size(); ++j)
    if (skeleton.joints[j].parent < 0) root = std::max(root, pose[j].translation().dot(up));
  return root - lowestJoint(pose, up);
}

}  // namespace

Retargeter::Retargeter(const Skeleton& source, const Skeleton& target, const JointMap& map,
                       const RetargetOptions& options, const std::string& mapSource)
    : target_(target), sourceRest_(source.restWorld()), targetRest_(target.restWorld()),
      driver_(target.joints.size(), -1), alignment_(target.joints.size(), Eigen::Matrix3d::Identity()),
      axes_(options.sourceAxes) {
  if (!((axes_ * axes_.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9 && axes_.determinant() > 0))
    throw UsageError("retargeting: the source axes are not a rotation");
  if (!(options.sourceUp.norm() > 0)) throw UsageError("retargeting: the up direction is zero");
  int matched = 0;
  for (const auto& [from, to] : map.pairs) {
    const int s = source.find(from), t = target.find(to);
    if (s < 0 || t < 0) {
      skipped_.push_back(from + " -> " + to);
      continue;
    }
    driver_[t] = s;
    ++matched;
    const Eigen::Vector3d ds = axes_ * (sourceRest_[s].linear() * boneDirection(source, s));
    const Eigen::Vector3d dt = targetRest_[t].linear() * boneDirection(target, t);
    if (options.alignRestDirections && ds.norm() > 0 && dt.norm() > 0)
      alignment_[t] = Eigen::Quaterniond::FromTwoVectors(dt, ds).toRotationMatrix();
  }
  if (matched == 0) throw BadInput(mapSource, "names no joint pair present in both skeletons");
  sourceStance_ = options.sourceStance.value_or(sourceRest_);
  if (sourceStance_.size() != sourceRest_.size())
    throw UsageError("retargeting: a stance of " + std::to_string(sourceStance_.size()) + " joints for a skeleton of " +
                     std::to_string(sourceRest_.size()));
  // Hip heights and the floor compared in the stance, not each in its own rest: MakeHuman's A-pose legs
  // do not stand as CMU's T-pose legs apart do. With no lift yet, pose() puts our root at its rest place.
  const Eigen::Vector3d up = options.sourceUp.normalized();
  const std::vector<Eigen::Isometry3d> targetInStance = pose(sourceStance_);
  const double sourceHeight = hipHeight(sourceStance_, source, up);
  const double targetHeight = hipHeight(targetInStance, target, axes_ * up);
  if (sourceHeight > 0 && targetHeight > 0) rootScale_ = targetHeight / sourceHeight;
  rootLift_ = (lowestJoint(targetRest_, axes_ * up) - lowestJoint(targetInStance, axes_ * up)) * (axes_ * up);
}

std::vector<Eigen::Isometry3d> Retargeter::pose(const std::vector<Eigen::Isometry3d>& sourceWorld) const {
  if (sourceWorld.size() != sourceRest_.size())
    throw UsageError("retargeting: a pose of " + std::to_string(sourceWorld.size()) + " joints for a skeleton of " +
                     std::to_string(sourceRest_.size()));
  std::vector<Eigen::Isometry3d> posed(target_.joints.size(), Eigen::Isometry3d::Identity());
  for (std::size_t t = 0; t < posed.size(); ++t) {
    const Joint& joint = target_.joints[t];
    const int s = driver_[t];
    const Eigen::Isometry3d parent = joint.parent < 0 ? Eigen::Isometry3d::Identity() : posed[joint.parent];
    if (s < 0) {
      posed[t] = parent * joint.restLocal;
      continue;
    }
    const Eigen::Matrix3d delta =
        axes_ * sourceWorld[s].linear() * sourceRest_[s].linear().transpose() * axes_.transpose();
    posed[t].linear() = delta * alignment_[t] * targetRest_[t].linear();
    posed[t].translation() =
        joint.parent < 0
            ? Eigen::Vector3d(targetRest_[t].translation() + rootLift_ +
                              rootScale_ * axes_ *
                                  (sourceWorld[s].translation() - sourceStance_[s].translation()))
            : Eigen::Vector3d(parent * joint.restLocal.translation());
  }
  return posed;
}

}  // namespace vesalius::posing
