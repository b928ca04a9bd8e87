#include "vesalius/core/skeleton.h"

#include "vesalius/core/error.h"

#include <set>

namespace vesalius {

int Skeleton::find(const std::string& name) const {
  for (std::size_t i = 0; i < joints.size(); ++i)
    if (joints[i].name == name) return int(i);
  return -1;
}

std::vector<Eigen::Isometry3d> Skeleton::restWorld() const {
  std::vector<Eigen::Isometry3d> world(joints.size());
  for (std::size_t i = 0; i < joints.size(); ++i)
    world[i] = joints[i].parent < 0 ? joints[i].restLocal : world[joints[i].parent] * joints[i].restLocal;
  return world;
}

void Skeleton::validate(const std::string& source) const {
  std::set<std::string> names;
  for (std::size_t i = 0; i < joints.size(); ++i) {
    if (joints[i].parent >= int(i) || joints[i].parent < -1)
      throw BadInput(source, "joint '" + joints[i].name + "' comes before its parent");
    if (!names.insert(joints[i].name).second)
      throw BadInput(source, "joint name '" + joints[i].name + "' appears twice");
    if (!joints[i].restLocal.matrix().allFinite())
      throw BadInput(source, "joint '" + joints[i].name + "' has a non-finite rest transform");
  }
}

std::vector<Eigen::Isometry3d> Motion::localPose(int frame) const {
  // BVH semantics: translation channels add to the rest offset; rotation channels compose in the
  // order listed (so "Zrotation Yrotation Xrotation" gives Rz·Ry·Rx), angles in degrees.
  const double kDegree = M_PI / 180.0;
  std::vector<Eigen::Isometry3d> local(skeleton.joints.size());
  Eigen::Index column = 0;
  for (std::size_t j = 0; j < skeleton.joints.size(); ++j) {
    Eigen::Vector3d translation = skeleton.joints[j].restLocal.translation();
    Eigen::Matrix3d rotation = skeleton.joints[j].restLocal.linear();
    for (Channel c : channels[j]) {
      const double v = values(frame, column++);
      switch (c) {
        case Channel::Xposition: translation.x() += v; break;
        case Channel::Yposition: translation.y() += v; break;
        case Channel::Zposition: translation.z() += v; break;
        case Channel::Xrotation: rotation = rotation * Eigen::AngleAxisd(v * kDegree, Eigen::Vector3d::UnitX()); break;
        case Channel::Yrotation: rotation = rotation * Eigen::AngleAxisd(v * kDegree, Eigen::Vector3d::UnitY()); break;
        case Channel::Zrotation: rotation = rotation * Eigen::AngleAxisd(v * kDegree, Eigen::Vector3d::UnitZ()); break;
      }
    }
    local[j].linear() = rotation;
    local[j].translation() = translation;
  }
  return local;
}

std::vector<Eigen::Isometry3d> Motion::worldPose(int frame) const {
  std::vector<Eigen::Isometry3d> world = localPose(frame);
  for (std::size_t j = 0; j < world.size(); ++j)
    if (skeleton.joints[j].parent >= 0) world[j] = world[skeleton.joints[j].parent] * world[j];
  return world;
}

}  // namespace vesalius
