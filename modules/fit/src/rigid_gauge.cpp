#include "vesalius/fit/rigid_gauge.h"

#include "vesalius/fit/polar_derivatives.h"

#include "vesalius/core/error.h"

#include <map>

namespace vesalius::fit {

RigidGauge::RigidGauge(const std::vector<PointConstraint>& D, const MatrixX3d& restV, const Eigen::VectorXd& x)
    : D_(D) {
  if (D.size() < 3) throw BadInput("", "an un-attached fit needs at least 3 landmarks or ICP markers");
  X_.resize(Eigen::Index(D.size()), 3);
  for (std::size_t j = 0; j < D.size(); ++j) {
    Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
    for (int i = 0; i < 4; ++i) p += D[j].weights[i] * restV.row(D[j].vertices[i]);
    X_.row(Eigen::Index(j)) = p;
  }
  Xbar_ = X_.colwise().mean().transpose();
  X_.rowwise() -= Xbar_.transpose();
  t_ = centroid(x) - Xbar_;
  R_ = polarRotation(covariance(x));
}

Eigen::Vector3d RigidGauge::centroid(const Eigen::VectorXd& x) const {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const PointConstraint& p : D_) c += constrainedPoint(p, x);
  return c / double(D_.size());
}

Eigen::Matrix3d RigidGauge::covariance(const Eigen::VectorXd& x) const {
  // Σ w (x_j − t) (X_j − X̄)ᵀ = Σ w x_j (X_j − X̄)ᵀ because the X_j − X̄ sum to zero.
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (std::size_t j = 0; j < D_.size(); ++j)
    M += constrainedPoint(D_[j], x) * X_.row(Eigen::Index(j));
  return M / double(D_.size());
}

Eigen::VectorXd RigidGauge::impose(const Eigen::VectorXd& x) const {
  const Eigen::Matrix3d rotation = R_ * polarRotation(covariance(x)).transpose();
  const Eigen::Vector3d shift = t_ + Xbar_ - rotation * centroid(x);
  Eigen::VectorXd y(x.size());
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) y.segment<3>(3 * v) = rotation * x.segment<3>(3 * v) + shift;
  return y;
}

Eigen::MatrixXd RigidGauge::constraintJacobian(const Eigen::VectorXd& x) const {
  // d centroid / d x_v = (Σ_j w b_jv) I;  dM / d x_{v,d} = e_d a_vᵀ with a_v = Σ_j w b_jv (X_j − X̄).
  std::map<int, std::pair<double, Eigen::Vector3d>> perVertex;
  const double w = 1.0 / double(D_.size());
  for (std::size_t j = 0; j < D_.size(); ++j)
    for (int i = 0; i < 4; ++i) {
      if (D_[j].weights[i] == 0.0) continue;
      auto& [b, a] = perVertex.try_emplace(D_[j].vertices[i], 0.0, Eigen::Vector3d::Zero()).first->second;
      b += w * D_[j].weights[i];
      a += w * D_[j].weights[i] * X_.row(Eigen::Index(j)).transpose();
    }
  const Eigen::Matrix3d M = covariance(x);
  const PolarDerivatives polar(M);
  const Eigen::Matrix3d& R = polar.rotation();
  const Matrix9d& dR = polar.first();
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(6, x.size());
  for (const auto& [v, ba] : perVertex) {
    const auto& [b, a] = ba;
    for (int d = 0; d < 3; ++d) {
      C(d, 3 * v + d) = b;
      Eigen::Matrix3d dM = Eigen::Matrix3d::Zero();
      dM.row(d) = a.transpose();
      const Eigen::Matrix<double, 9, 1> dvecR = dR * Eigen::Map<const Eigen::Matrix<double, 9, 1>>(dM.data());
      const Eigen::Matrix3d skew = R.transpose() * Eigen::Map<const Eigen::Matrix3d>(dvecR.data());
      C.block<3, 1>(3, 3 * v + d) = Eigen::Vector3d(skew(2, 1), skew(0, 2), skew(1, 0));
    }
  }
  return C;
}

Eigen::MatrixXd rigidModes(const Eigen::VectorXd& x) {
  const Eigen::Index n = x.size() / 3;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < n; ++v) c += x.segment<3>(3 * v);
  c /= double(n);
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(x.size(), 6);
  for (Eigen::Index v = 0; v < n; ++v) {
    const Eigen::Vector3d r = x.segment<3>(3 * v) - c;
    for (int i = 0; i < 3; ++i) {
      N(3 * v + i, i) = 1.0;
      N.block<3, 1>(3 * v, 3 + i) = Eigen::Vector3d::Unit(i).cross(r);
    }
  }
  return N;
}

}  // namespace vesalius::fit
