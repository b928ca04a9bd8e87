#include "vesalius/posing/bone_frame.h"

#include "vesalius/core/error.h"

#include <Eigen/Geometry>

namespace vesalius::posing {

Eigen::Matrix3d boneFrame(int firstAxis, const Eigen::Vector3d& first, int secondAxis, const Eigen::Vector3d& second) {
  if (firstAxis < 0 || firstAxis > 2 || secondAxis < 0 || secondAxis > 2 || firstAxis == secondAxis)
    throw UsageError("boneFrame: the two axes must be distinct indices 0, 1 or 2");
  if (!(first.norm() > 0) || !(second.norm() > 0)) throw BadInput("", "a bone frame direction is zero or not finite");
  const Eigen::Vector3d a = first.normalized();
  const Eigen::Vector3d rest = second - second.dot(a) * a;
  if (!(rest.norm() > 1e-9 * second.norm())) throw BadInput("", "the two directions of a bone frame are parallel");
  const Eigen::Vector3d b = rest.normalized();
  Eigen::Matrix3d frame;
  frame.col(firstAxis) = a;
  frame.col(secondAxis) = b;
  // x × y = z, y × z = x, z × x = y: the third follows the cyclic order of the two given.
  const int third = 3 - firstAxis - secondAxis;
  frame.col(third) = secondAxis == (firstAxis + 1) % 3 ? a.cross(b) : b.cross(a);
  return frame;
}

Eigen::Isometry3d placedFrame(const Eigen::Matrix3d& axes, const Eigen::Vector3d& origin) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = axes;
  T.translation() = origin;
  return T;
}

}  // namespace vesalius::posing
