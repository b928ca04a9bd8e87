#include "vesalius/fit/equilibrium_jacobian.h"

#include <Eigen/LU>
#include <Eigen/QR>

#include <algorithm>
#include <utility>

namespace vesalius::fit {
namespace {

// The six coordinates along which the rigid modes are best determined: the first pivots of a
// column-pivoted QR of Nᵀ.
std::vector<Eigen::Index> rigidPins(const Eigen::MatrixXd& N) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(N.transpose());
  std::vector<Eigen::Index> pins;
  for (int i = 0; i < 6; ++i) pins.push_back(qr.colsPermutation().indices()[i]);
  std::sort(pins.begin(), pins.end());
  return pins;
}

// K with the pinned rows and columns replaced by those of the identity, keeping its sparsity pattern so
// the Cholesky analysis stays valid.
void pin(Eigen::SparseMatrix<double>& K, const std::vector<Eigen::Index>& pins) {
  std::vector<char> isPinned(std::size_t(K.rows()), 0);
  for (Eigen::Index p : pins) isPinned[std::size_t(p)] = 1;
  for (Eigen::Index j = 0; j < K.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, j); it; ++it)
      if (isPinned[std::size_t(it.row())] || isPinned[std::size_t(it.col())])
        it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
}

}  // namespace

EquilibriumJacobian::EquilibriumJacobian(Eigen::SparseMatrix<double> K, Eigen::SparseMatrix<double> G,
                                         const Eigen::VectorXd& x, const RigidGauge* gauge,
                                         SparseCholesky& cholesky)
    : G_(std::move(G)), cholesky_(cholesky) {
  if (gauge) {
    N_ = rigidModes(x);
    C_ = gauge->constraintJacobian(x);
    CNinverse_ = (C_ * N_).inverse();
    pinned_ = rigidPins(N_);
    pin(K, pinned_);
  }
  cholesky_.factor(K);
}

Eigen::MatrixXd EquilibriumJacobian::solvePinned(Eigen::MatrixXd B) const {
  for (Eigen::Index p : pinned_) B.row(p).setZero();
  cholesky_.solveInPlace(B);
  for (Eigen::Index p : pinned_) B.row(p).setZero();
  return B;
}

Eigen::MatrixXd EquilibriumJacobian::equilibriumChange(const Eigen::MatrixXd& forceChange) const {
  Eigen::MatrixXd dx = solvePinned(-forceChange);
  if (N_.size()) dx -= N_ * (CNinverse_ * (C_ * dx));
  return dx;
}

ConstraintJacobian EquilibriumJacobian::constraintJacobian(const Eigen::SparseMatrix<double>& rows) const {
  // Solve on the side with fewer columns: J itself for a few parameters (the constant-strain stage's 6),
  // otherwise Z = A P E K_ff⁻¹ Eᵀ (−G) = −Wᵀ G with W = K_ff⁻¹ (Pᵀ Aᵀ) on the free coordinates.
  if (G_.cols() < rows.rows()) return ConstraintJacobian(Eigen::MatrixXd(rows * equilibriumChange(Eigen::MatrixXd(G_))));
  Eigen::MatrixXd U = Eigen::MatrixXd(rows.transpose());
  if (N_.size()) U -= C_.transpose() * (CNinverse_.transpose() * (N_.transpose() * U));
  return ConstraintJacobian(solvePinned(std::move(U)).transpose(), G_);
}

Eigen::VectorXd EquilibriumJacobian::apply(const Eigen::VectorXd& ds) const {
  return equilibriumChange(Eigen::MatrixXd(G_ * ds)).col(0);
}

}  // namespace vesalius::fit
