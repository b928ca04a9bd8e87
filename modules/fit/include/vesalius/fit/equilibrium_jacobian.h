// The Jacobian of the equilibrium with respect to the plastic parameters, used without forming it
// (Wang et al. 2021, eqs. 10 and 12): J = dx/ds = −K⁻¹ G with K = ∂f/∂x (3#V by 3#V) and G = ∂f/∂s (3#V by 6#T).
// J is dense (3#V by 6#T); the fitter needs only Z = √c A J for the few constraint rows, so K is
// factored once and solved for the 3#C columns of (√c A)ᵀ at once: Z = −(K⁻¹ (√c A)ᵀ)ᵀ G, kept as
// those two factors (constraint_jacobian.h).
//
// Un-attached objects (§3.6): K is singular with the six rigid motions N as its nullspace. Pinning the six
// degrees of freedom that best determine N makes the rest of K definite and gives one solution of
// K dx = −G ds; the gauge constraints C dx = 0 (rigid_gauge.h) then select the one the fitter uses,
// dx = P dx_pinned with the oblique projector P = I − N (C N)⁻¹ C (K N = 0, so P keeps the equilibrium).
// This is the paper's Singular Lemma (ii) route reached through a pinned, positive-definite factorization.
#pragma once

#include "vesalius/fit/constraint_jacobian.h"
#include "vesalius/fit/rigid_gauge.h"

#include "vesalius/linalg/sparse_cholesky.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace vesalius::fit {

class EquilibriumJacobian {
 public:
  // K: symmetric, positive definite (attached) or positive semi-definite with the rigid nullspace
  // (gauge given). Factors it into `cholesky`, whose symbolic analysis is reused across iterations.
  // Throws NumericalFailure if K (pinned) is not positive definite.
  EquilibriumJacobian(Eigen::SparseMatrix<double> K, Eigen::SparseMatrix<double> G,
                      const Eigen::VectorXd& x, const RigidGauge* gauge, SparseCholesky& cholesky);

  // Z = √c A J for constraint rows √c A (3#C by 3#V): 3#C by 6#T.
  ConstraintJacobian constraintJacobian(const Eigen::SparseMatrix<double>& rows) const;
  // J ds: the first-order change of the equilibrium (3#V) for a change ds (6#T) of the plastic parameters.
  Eigen::VectorXd apply(const Eigen::VectorXd& ds) const;

 private:
  Eigen::MatrixXd solvePinned(Eigen::MatrixXd B) const;
  // P K⁻¹ (−dG): the equilibrium's change (3#V by k) for force changes dG (3#V by k), in the gauge.
  Eigen::MatrixXd equilibriumChange(const Eigen::MatrixXd& forceChange) const;

  Eigen::SparseMatrix<double> G_;
  SparseCholesky& cholesky_;
  std::vector<Eigen::Index> pinned_;
  Eigen::MatrixXd N_, C_;            // rigid modes (3#V by 6), gauge rows (6 by 3#V); empty when attached
  Eigen::Matrix<double, 6, 6> CNinverse_;
};

}  // namespace vesalius::fit
