#include "vesalius/posing/skeleton_pose.h"

#include "vesalius/core/error.h"

namespace vesalius::posing {

std::vector<Eigen::Isometry3d> restToPosed(const Skeleton& skeleton, const std::vector<Eigen::Isometry3d>& posedWorld) {
  if (posedWorld.size() != skeleton.joints.size())
    throw UsageError("restToPosed: " + std::to_string(posedWorld.size()) + " poses for " +
                     std::to_string(skeleton.joints.size()) + " joints");
  const std::vector<Eigen::Isometry3d> rest = skeleton.restWorld();
  std::vector<Eigen::Isometry3d> transforms(rest.size());
  for (std::size_t j = 0; j < rest.size(); ++j) transforms[j] = posedWorld[j] * rest[j].inverse();
  return transforms;
}

}  // namespace vesalius::posing
