#include "vesalius/fit/polar_derivatives.h"

#include "vesalius/core/error.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include <string>

namespace vesalius::fit {

namespace {

using Vector9d = Eigen::Matrix<double, 9, 1>;

Eigen::Matrix3d unit(int i) {
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(i % 3, i / 3) = 1.0;
  return E;
}

Eigen::Map<const Vector9d> vec(const Eigen::Matrix3d& M) { return Eigen::Map<const Vector9d>(M.data()); }

Eigen::Matrix3d unvec(const Vector9d& v) { return Eigen::Map<const Eigen::Matrix3d>(v.data()); }

struct Polar {
  Eigen::Matrix3d R, S, Sinv;
};

// Through the SVD F = U Σ Vᵀ: R = U Vᵀ, S = V Σ Vᵀ. det F > 0 makes det(U Vᵀ) = +1 and Σ invertible.
Polar decompose(const Eigen::Matrix3d& F) {
  const double det = F.determinant();
  if (!(det > 0.0))
    throw NumericalFailure("polar decomposition: det F = " + std::to_string(det) + " is not positive");
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  if (!(sigma.minCoeff() > 0.0)) throw NumericalFailure("polar decomposition: F is singular");
  const Eigen::Matrix3d& V = svd.matrixV();
  return {svd.matrixU() * V.transpose(), V * sigma.asDiagonal() * V.transpose(),
          V * sigma.cwiseInverse().asDiagonal() * V.transpose()};
}

// S ⊕ S = I ⊗ S + S ⊗ I: vec(X S + S X) = (S ⊕ S) vec(X) for symmetric S (eq. 23).
Matrix9d kroneckerSum(const Eigen::Matrix3d& S) {
  Matrix9d K = Matrix9d::Zero();
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q)
      for (int r = 0; r < 3; ++r) {
        K(3 * p + r, 3 * q + r) += S(p, q);
        K(3 * r + p, 3 * r + q) += S(p, q);
      }
  return K;
}

}  // namespace

Eigen::Matrix3d polarRotation(const Eigen::Matrix3d& F) { return decompose(F).R; }

PolarDerivatives::PolarDerivatives(const Eigen::Matrix3d& F) {
  const Polar polar = decompose(F);
  R_ = polar.R;
  S_ = polar.S;
  Sinv_ = polar.Sinv;
  kroneckerSum_.compute(kroneckerSum(S_));
  // Eq. 22: ∂S/∂F_i S + S ∂S/∂F_i = ∂(FᵀF)/∂F_i = E_iᵀ F + Fᵀ E_i, all nine right-hand sides at once.
  Matrix9d rhs;
  for (int i = 0; i < 9; ++i) {
    const Eigen::Matrix3d EtF = unit(i).transpose() * F;
    rhs.col(i) = vec(EtF + EtF.transpose());
  }
  const Matrix9d dS = kroneckerSum_.solve(rhs);
  for (int i = 0; i < 9; ++i) {
    dS_[i] = unvec(dS.col(i));
    dRm_[i] = (unit(i) - R_ * dS_[i]) * Sinv_;  // eq. 21
    dR_.col(i) = vec(dRm_[i]);
  }
}

std::array<Matrix9d, 9> PolarDerivatives::second() const {
  // Eqs. 49-51 for each pair i <= j; ∂²(FᵀF)/∂F_i∂F_j = E_iᵀ E_j + E_jᵀ E_i.
  Eigen::Matrix<double, 9, 45> rhs;
  for (int i = 0, n = 0; i < 9; ++i)
    for (int j = i; j < 9; ++j, ++n) {
      const Eigen::Matrix3d EE = unit(i).transpose() * unit(j), SS = dS_[i] * dS_[j];
      rhs.col(n) = vec(EE + EE.transpose() - SS - SS.transpose());
    }
  const Eigen::Matrix<double, 9, 45> d2S = kroneckerSum_.solve(rhs);
  std::array<Matrix9d, 9> hessians;
  for (int i = 0, n = 0; i < 9; ++i)
    for (int j = i; j < 9; ++j, ++n) {
      // Eq. 48.
      const Eigen::Matrix3d d2R = -(R_ * unvec(d2S.col(n)) + dRm_[j] * dS_[i] + dRm_[i] * dS_[j]) * Sinv_;
      for (int k = 0; k < 9; ++k) hessians[k](i, j) = hessians[k](j, i) = d2R.data()[k];
    }
  return hessians;
}

}  // namespace vesalius::fit
