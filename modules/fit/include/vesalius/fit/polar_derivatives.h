// Rotation of the polar decomposition and its first and second derivatives (Wang et al. 2021, §3.7, eqs. 21-24;
// Appendix E, eqs. 46-51).
//
// Polar(F) = R with F = R S, S = sqrt(FᵀF) symmetric positive definite. The rotational stabilization
// constraint of un-attached objects (eq. 20) needs ∂R/∂F and ∂²R/∂F², per entry of F. Both follow from
// differentiating F = R S and FᵀF = S² and solving Sylvester equations with the Kronecker sum S ⊕ S,
// which is factored once per F.
//
// Layout: vec is column-major, so entry i of vec(F) is F(i % 3, i / 3).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <array>

namespace vesalius::fit {

using Matrix9d = Eigen::Matrix<double, 9, 9>;

// R = Polar(F). Throws NumericalFailure unless det F > 0 (an inversion has no rotation as polar factor).
Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& F);

class PolarDerivatives {
 public:
  // Computes R, S and the first derivatives. Throws NumericalFailure unless det F > 0.
  explicit PolarDerivatives(const Eigen::Matrix3d& F);

  const Eigen::Matrix3d& rotation() const { return R_; }
  const Eigen::Matrix3d& stretch() const { return S_; }

  // 9 by 9: entry (k, i) = ∂vec(R)_k / ∂vec(F)_i.
  const Matrix9d& first() const { return dR_; }

  // 9 matrices, each 9 by 9 and symmetric: second()[k](i, j) = ∂²vec(R)_k / ∂vec(F)_i ∂vec(F)_j,
  // i.e. the Hessian of entry k of R. Computed on demand (45 more 9 by 9 solves).
  std::array<Matrix9d, 9> second() const;

 private:
  Eigen::Matrix3d R_, S_, Sinv_;
  Eigen::LLT<Matrix9d> kroneckerSum_;  // S ⊕ S, SPD: its eigenvalues are sums of two eigenvalues of S
  std::array<Eigen::Matrix3d, 9> dS_, dRm_;  // ∂S/∂F_i and ∂R/∂F_i as matrices
  Matrix9d dR_;
};

}  // namespace vesalius::fit
