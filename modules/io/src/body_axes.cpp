// Axes and units of bodies and motions (body_axes.h).
#include "vesalius/io/body_axes.h"

#include "vesalius/core/error.h"

namespace vesalius::io {

Eigen::Matrix3d yUpToLps() {
  Eigen::Matrix3d axes;
  axes << 1, 0, 0,  //
      0, 0, -1,     //
      0, 1, 0;
  return axes;
}

Eigen::Matrix3d openSimToLps() {
  Eigen::Matrix3d axes;
  axes << 0, 0, -1,  //
      -1, 0, 0,      //
      0, 1, 0;
  return axes;
}

MatrixX3d transformPoints(const MatrixX3d& P, const Eigen::Matrix3d& axes, double scale) {
  return scale * P * axes.transpose();
}

Skeleton transformSkeleton(const Skeleton& skeleton, const Eigen::Matrix3d& axes, double scale) {
  if (!((axes * axes.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-9 && axes.determinant() > 0))
    throw UsageError("transformSkeleton: the axes are not a rotation");
  if (!(scale > 0)) throw UsageError("transformSkeleton: the scale must be positive");
  // A local transform L = P⁻¹ X of world frames P, X becomes (A P Aᵀ)⁻¹ (A X Aᵀ) = A L Aᵀ, with the
  // translations scaled; tails are vectors in the joint's frame, which rotates with it.
  Skeleton out = skeleton;
  for (Joint& joint : out.joints) {
    const Eigen::Matrix3d r = axes * joint.restLocal.linear() * axes.transpose();
    const Eigen::Vector3d t = scale * axes * joint.restLocal.translation();
    joint.restLocal.linear() = r;
    joint.restLocal.translation() = t;
    joint.tail = scale * axes * joint.tail;
  }
  return out;
}

}  // namespace vesalius::io
