// The Gauss-Newton search direction: solve H y = h for H = L² + ZᵀZ (Wang et al. 2021, §3.4, eqs. 11-14).
//
// H is 6#T by 6#T and dense (ZᵀZ is; Z is #C by 6#T, #C = 3 × constraints, a few hundred), so it is never
// formed. WoodburySolver splits H = B + ẐᵀẐ with the invertible sparse-factored B = L² − Σ ψᵢψᵢᵀ and
// Ẑ = [Z; ψᵀ] (eq. 13) and applies Woodbury's identity (eq. 14):
//   y = B⁻¹ (h − Ẑᵀ w),  (I + Ẑ B⁻¹ Ẑᵀ) w = Ẑ B⁻¹ h.
// The (#C + 6) square capacitance matrix is formed and LU-factored once per Z. It is indefinite (B is), so
// its factorization pivots. solveConjugateGradient is the paper's matrix-free CG baseline for the same H.
//
// Ours: a Levenberg-Marquardt damping μ D with D = L² + Σψψᵀ (SPD) keeps the same structure: H + μD =
// B_μ + Ẑ_μᵀẐ_μ with B_μ = (1+μ) L² − Σψψᵀ, so the one factorization of L still serves, and changing μ
// re-forms only the small capacitance matrix. The fitter raises μ when the Gauss-Newton step fails.
#pragma once

#include "vesalius/fit/constraint_jacobian.h"
#include "vesalius/fit/plastic_laplacian.h"

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/SparseCore>

namespace vesalius::fit {

class WoodburySolver {
 public:
  // base: factored once per mesh and must outlive this solver. Z: #C by 6#T (columns tet-major), kept
  // for the solves. mu: the first damping (see setDamping). Throws BadInput on a size
  // mismatch, NumericalFailure if the capacitance matrix is singular (with μ = 0: H is singular, Z does
  // not constrain the nullspace ψ of L, as with fewer landmarks than an un-attached object's rigid motions).
  WoodburySolver(const SmoothnessBaseSolver& base, ConstraintJacobian Z, double mu = 0.0);

  // Solves with H + μ (L² + Σψψᵀ) from now on (μ ≥ 0): one LU of the (#C + 6)² capacitance matrix,
  // nothing when μ is the current damping.
  void setDamping(double mu);

  // h: 6#T by K. Returns H⁻¹h (6#T by K): two base solves on K columns plus products with Z, refined
  // (at most 3 more rounds) until ||h − H y|| <= 1e-10 ||h||. Throws NumericalFailure if the capacitance
  // solve has a normwise backward error above 1e-10.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& h) const;
  // One application of eq. 14 without the refinement: close enough to measure a trial step (the fitter's
  // trust region tries several dampings), at a third of the cost.
  Eigen::MatrixXd solveUnrefined(const Eigen::MatrixXd& h) const { return solveOnce(h); }
  // The refinement of solve() from an approximation y of H⁻¹h.
  Eigen::MatrixXd refine(const Eigen::MatrixXd& h, Eigen::MatrixXd y) const;
  // Z as given (#C by 6#T), for callers that handed theirs over.
  const ConstraintJacobian& Z() const { return Z_; }

 private:
  static constexpr int kRefinements = 3;
  static constexpr double kRefinedResidual = 1e-10;

  Eigen::MatrixXd solveOnce(const Eigen::MatrixXd& h) const;
  Eigen::MatrixXd applyH(const Eigen::MatrixXd& y) const;  // L² y + Zᵀ (Z y)

  const SmoothnessBaseSolver* base_;
  ConstraintJacobian Z_;
  Eigen::MatrixXd psi_;     // 6#T by 6, the nullspace of L
  Eigen::MatrixXd smooth_;  // Z (L²)⁺ Zᵀ, #C by #C: the expensive part, computed once
  Eigen::MatrixXd Zpsi_;    // Z ψ, #C by 6
  double mu_ = 0.0;
  bool factored_ = false;  // the LU is that of mu_
  Eigen::MatrixXd capacitance_;  // I + Ẑ B⁻¹ Ẑᵀ, kept for the residual check
  Eigen::VectorXd scale_;        // equilibration: the LU is of diag(scale) capacitance diag(scale)
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitanceLu_;
};

struct ConjugateGradientResult {
  Eigen::VectorXd y;        // 6#T
  int iterations;           // matrix products with H
  double relativeResidual;  // ||h − H y|| / ||h||
};

// Unpreconditioned CG on H y = h with H y = L(L y) + Zᵀ(Z y) applied matrix-free; Lsc: #T by #T,
// Z: #C by 6#T, h: 6#T. Starts from y = 0 and stops when the relative residual is at most `tolerance`
// or after `maxIterations`; not converging is reported in the result, not thrown.
ConjugateGradientResult solveConjugateGradient(const Eigen::SparseMatrix<double>& Lsc, const ConstraintJacobian& Z,
                                               const Eigen::VectorXd& h, double tolerance, int maxIterations);

}  // namespace vesalius::fit
