#include "vesalius/fit/woodbury.h"

#include "vesalius/core/error.h"

#include <cmath>
#include <string>

namespace vesalius::fit {

using Eigen::Index;

WoodburySolver::WoodburySolver(const SmoothnessBaseSolver& base, ConstraintJacobian Z, double mu)
    : base_(&base), Z_(std::move(Z)), psi_(plasticLaplacianNullspace(base.tetCount())) {
  if (Z_.cols() != 6 * base.tetCount()) throw BadInput("", "Woodbury solver: Z has the wrong number of columns");
  Zpsi_ = Z_ * psi_;
  smooth_ = base.sandwich(Z_, Zpsi_);
  setDamping(mu);
}

// With damping μ, H_μ = (1+μ) L² + μ Σψψᵀ + ZᵀZ = B_μ + ẐᵀẐ for B_μ = (1+μ) L² − Σψψᵀ and
// Ẑ = [Z; √(1+μ) ψᵀ]. As B_μ⁻¹ψ = −ψ and Z (L²)⁺ψ = 0, the capacitance I + Ẑ B_μ⁻¹ Ẑᵀ is
//   [ I + Z(L²)⁺Zᵀ/(1+μ) − (Zψ)(Zψ)ᵀ    −√(1+μ) Zψ ]
//   [ −√(1+μ) (Zψ)ᵀ                     −μ I       ]   (μ = 0: eq. 14's, with a zero ψψ block).
void WoodburySolver::setDamping(double mu) {
  if (!(mu >= 0.0)) throw BadInput("", "Woodbury solver: damping must be >= 0");
  if (factored_ && mu == mu_) return;
  factored_ = false;
  mu_ = mu;
  const Index C = Z_.rows();
  const double root = std::sqrt(1.0 + mu);
  capacitance_.resize(C + 6, C + 6);
  capacitance_.topLeftCorner(C, C) = smooth_ / (1.0 + mu) - Zpsi_ * Zpsi_.transpose();
  capacitance_.topLeftCorner(C, C).diagonal().array() += 1.0;
  capacitance_.topRightCorner(C, 6) = -root * Zpsi_;
  capacitance_.bottomLeftCorner(6, C) = -root * Zpsi_.transpose();
  capacitance_.bottomRightCorner(6, 6) = -mu * Eigen::MatrixXd::Identity(6, 6);
  // Z(L²)⁺Zᵀ reaches 1e12 and more beside the identity and the ψψ block: equilibrate by the square roots
  // of the diagonal before the LU, so that the condition estimate and the pivoting see the problem rather
  // than its units.
  scale_ = capacitance_.diagonal().cwiseAbs().cwiseMax(1.0).cwiseSqrt().cwiseInverse();
  capacitanceLu_.compute(scale_.asDiagonal() * capacitance_ * scale_.asDiagonal());
  if (!(capacitanceLu_.rcond() > 1e-14))
    throw NumericalFailure("Woodbury solver: H = L² + ZᵀZ is singular (Z does not constrain the plastic strain nullspace)");
  factored_ = true;
}

Eigen::MatrixXd WoodburySolver::solveOnce(const Eigen::MatrixXd& h) const {
  const Index C = Z_.rows();
  const double scale = 1.0 + mu_, root = std::sqrt(scale);
  const Eigen::MatrixXd u = base_->solve(h, scale);
  Eigen::MatrixXd v(C + 6, h.cols());
  v.topRows(C) = Z_ * u;
  v.bottomRows(6) = root * (psi_.transpose() * u);
  const Eigen::MatrixXd w = scale_.asDiagonal() * capacitanceLu_.solve(scale_.asDiagonal() * v);
  const double backwardError = (capacitance_ * w - v).norm() / (capacitance_.norm() * w.norm() + v.norm());
  if (!(backwardError <= 1e-10 || v.norm() == 0.0))
    throw NumericalFailure("Woodbury solver: the capacitance solve failed (backward error " +
                           std::to_string(backwardError) + ")");
  return base_->solve(h - Z_.transposeTimes(w.topRows(C)) - root * (psi_ * w.bottomRows(6)), scale);
}

Eigen::MatrixXd WoodburySolver::solve(const Eigen::MatrixXd& h) const { return refine(h, solveOnce(h)); }

Eigen::MatrixXd WoodburySolver::refine(const Eigen::MatrixXd& h, Eigen::MatrixXd y) const {
  // Woodbury subtracts B⁻¹-sized terms to get a much smaller H⁻¹h; when cond(H) is large the round-off
  // left is removed by iterative refinement with the exact, matrix-free H.
  for (int round = 0; round < kRefinements; ++round) {
    const Eigen::MatrixXd residual = h - applyH(y);
    if (residual.norm() <= kRefinedResidual * h.norm()) break;
    y += solveOnce(residual);
  }
  return y;
}

Eigen::MatrixXd WoodburySolver::applyH(const Eigen::MatrixXd& y) const {
  Eigen::MatrixXd Hy = Z_.transposeTimes(Z_ * y) + mu_ * (psi_ * (psi_.transpose() * y));
  for (Index k = 0; k < y.cols(); ++k)
    Hy.col(k) += (1.0 + mu_) *
                 applyPlasticLaplacian(base_->laplacian(), applyPlasticLaplacian(base_->laplacian(), y.col(k)));
  return Hy;
}

ConjugateGradientResult solveConjugateGradient(const Eigen::SparseMatrix<double>& Lsc, const ConstraintJacobian& Z,
                                               const Eigen::VectorXd& h, double tolerance, int maxIterations) {
  if (Z.cols() != h.size() || h.size() != 6 * Lsc.rows())
    throw BadInput("", "conjugate gradients: Z, h and Lsc do not have matching sizes");
  const auto applyH = [&](const Eigen::VectorXd& p) -> Eigen::VectorXd {
    return applyPlasticLaplacian(Lsc, applyPlasticLaplacian(Lsc, p)) + Z.transposeTimes(Z * p);
  };
  const double hNorm = h.norm();
  ConjugateGradientResult result{Eigen::VectorXd::Zero(h.size()), 0, 0.0};
  if (hNorm == 0.0) return result;
  Eigen::VectorXd r = h, p = h;
  double rr = r.squaredNorm();
  while (result.iterations < maxIterations && std::sqrt(rr) > tolerance * hNorm) {
    const Eigen::VectorXd Hp = applyH(p);
    const double alpha = rr / p.dot(Hp);
    result.y += alpha * p;
    r -= alpha * Hp;
    const double rrNext = r.squaredNorm();
    p = r + (rrNext / rr) * p;
    rr = rrNext;
    ++result.iterations;
  }
  result.relativeResidual = (h - applyH(result.y)).norm() / hNorm;
  return result;
}

}  // namespace vesalius::fit
