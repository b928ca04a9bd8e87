// Stable neo-Hookean elasticity (Smith, de Goes, Kim, "Stable Neo-Hookean Flesh Simulation", ACM TOG 37(2),
// 2018): the isotropic energy density ψ that Wang et al. 2021 uses in its plastic elastic energy (§3.2, eq. 1).
//
//   ψ(F) = μ/2 (I_C − 3) + λ/2 (J − α)² − μ/2 log(I_C + 1) − ψ0,   I_C = tr(FᵀF), J = det F,
//   α = 1 + 3μ/(4λ) makes the rest state stress-free (P(I) = 0), and the constant
//   ψ0 = 9μ²/(32λ) − μ/2 log 4 makes ψ(I) = 0 (so a body at its plastic rest shape has zero energy).
//
// ψ is smooth for every F, inverted ones (J ≤ 0) included. μ and λ here are Smith's parameters, not the
// Lamé ones: matching the linearization at F = I to linear elasticity gives μ = 4/3 μ_L and
// λ = λ_L + 5/6 μ_L (Smith et al., "Lamé reparameterization"), with μ_L = E / (2(1 + ν)) and
// λ_L = E ν / ((1 + ν)(1 − 2ν)).
// Stress unit = the unit of E (e.g. kPa); energy density likewise.
#pragma once

#include <Eigen/Core>

namespace vesalius {

struct StableNeoHookean {
  double mu = 0, lambda = 0;  // Smith's μ and λ; both > 0

  // Throws BadInput unless young > 0 and −1 < poisson < 1/2.
  static StableNeoHookean fromYoungPoisson(double young, double poisson);

  double energy(const Eigen::Matrix3d& F) const;
  // First Piola-Kirchhoff stress P = dψ/dF.
  Eigen::Matrix3d stress(const Eigen::Matrix3d& F) const;
  // d vec(P) / d vec(F), vec column-major; symmetric.
  Eigen::Matrix<double, 9, 9> stressDerivative(const Eigen::Matrix3d& F) const;
  // The same with negative eigenvalues set to zero: positive semi-definite, so Newton steps descend.
  Eigen::Matrix<double, 9, 9> projectedStressDerivative(const Eigen::Matrix3d& F) const;

 private:
  double alpha() const { return 1 + 0.75 * mu / lambda; }
};

}  // namespace vesalius
