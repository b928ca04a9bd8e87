// Dual quaternion skinning (dual_quaternion_skinning.h).
#include "vesalius/posing/dual_quaternion_skinning.h"

#include "blending.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vesalius::posing {
namespace {

// Dual parts ½ t_j q_j, as (x, y, z, w) coefficients.
std::vector<Eigen::Vector4d> dualParts(const std::vector<Eigen::Isometry3d>& transforms,
                                       const std::vector<Eigen::Vector4d>& real) {
  std::vector<Eigen::Vector4d> dual;
  for (std::size_t j = 0; j < transforms.size(); ++j) {
    const Eigen::Vector3d t = transforms[j].translation();
    const Eigen::Quaterniond q(real[j]);
    dual.push_back(0.5 * (Eigen::Quaterniond(0.0, t.x(), t.y(), t.z()) * q).coeffs());
  }
  return dual;
}

// Applies the rigid motion of the dual quaternion (real, dual) / |real| to v.
Eigen::Vector3d applyDualQuaternion(const Eigen::Vector4d& real, const Eigen::Vector4d& dual, const Eigen::Vector3d& v) {
  const double norm = real.norm();
  const Eigen::Vector4d c0 = real / norm, ce = dual / norm;
  const Eigen::Vector3d r = c0.head<3>(), d = ce.head<3>();
  const Eigen::Vector3d t = 2.0 * (c0.w() * d - ce.w() * r + r.cross(d));
  return Eigen::Quaterniond(c0) * v + t;
}

}  // namespace

MatrixX3d dualQuaternionSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                                 const std::vector<Eigen::Isometry3d>& transforms) {
  detail::checkSkinningInputs(V, W, transforms, "dual quaternion skinning");
  const std::vector<Eigen::Vector4d> real = detail::rotationQuaternions(transforms);
  const std::vector<Eigen::Vector4d> dual = dualParts(transforms, real);
  MatrixX3d posed(V.rows(), 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, V.rows(), 1024), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index i = r.begin(); i < r.end(); ++i) {
      Eigen::Index heaviest = 0;
      W.row(i).maxCoeff(&heaviest);
      Eigen::Vector4d b0 = Eigen::Vector4d::Zero(), be = Eigen::Vector4d::Zero();
      for (Eigen::Index j = 0; j < W.cols(); ++j) {
        if (W(i, j) == 0.0) continue;
        const double w = W(i, j) * detail::hemisphereSign(real[std::size_t(j)], real[std::size_t(heaviest)]);
        b0 += w * real[std::size_t(j)];
        be += w * dual[std::size_t(j)];
      }
      posed.row(i) = applyDualQuaternion(b0, be, V.row(i).transpose()).transpose();
    }
  });
  return posed;
}

}  // namespace vesalius::posing
