#include "vesalius/fem/stable_neo_hookean.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/determinant.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>
#include <string>

namespace vesalius {

using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;

StableNeoHookean StableNeoHookean::fromYoungPoisson(double young, double poisson) {
  if (!(young > 0) || !(poisson > -1 && poisson < 0.5))
    throw BadInput("", "stable neo-Hookean needs Young's modulus > 0 and -1 < Poisson's ratio < 0.5, got " +
                           std::to_string(young) + " and " + std::to_string(poisson));
  const double muLame = young / (2 * (1 + poisson));
  const double lambdaLame = young * poisson / ((1 + poisson) * (1 - 2 * poisson));
  return {4.0 / 3.0 * muLame, lambdaLame + 5.0 / 6.0 * muLame};
}

// ψ0 folded in: (J − α)² − (1 − α)² = (J − 1)(J + 1 − 2α) and log(I_C + 1) − log 4 = log1p((I_C − 3)/4),
// so ψ(I) is exactly 0 and small strains lose no digits to cancellation.
double StableNeoHookean::energy(const Eigen::Matrix3d& F) const {
  const double ic3 = F.squaredNorm() - 3, j = F.determinant();
  return 0.5 * mu * ic3 + 0.5 * lambda * (j - 1) * (j + 1 - 2 * alpha()) - 0.5 * mu * std::log1p(ic3 / 4);
}

Eigen::Matrix3d StableNeoHookean::stress(const Eigen::Matrix3d& F) const {
  const double ic = F.squaredNorm();
  return mu * (1 - 1 / (ic + 1)) * F + lambda * (F.determinant() - alpha()) * determinantGradient(F);
}

Matrix9d StableNeoHookean::stressDerivative(const Eigen::Matrix3d& F) const {
  const double ic = F.squaredNorm();
  const Eigen::Matrix3d cof = determinantGradient(F);
  const Eigen::Map<const Vector9d> f(F.data()), g(cof.data());
  Matrix9d H = mu * (1 - 1 / (ic + 1)) * Matrix9d::Identity();
  H += (2 * mu / ((ic + 1) * (ic + 1))) * f * f.transpose() + lambda * g * g.transpose();
  H += lambda * (F.determinant() - alpha()) * determinantHessian(F);
  return H;
}

Matrix9d StableNeoHookean::projectedStressDerivative(const Eigen::Matrix3d& F) const {
  const Eigen::SelfAdjointEigenSolver<Matrix9d> eig(stressDerivative(F));
  const Vector9d clamped = eig.eigenvalues().cwiseMax(0.0);
  return eig.eigenvectors() * clamped.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace vesalius
