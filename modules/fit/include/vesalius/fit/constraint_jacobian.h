// The constraint rows of the equilibrium Jacobian, Z = √c A J (#C by 6#T; Wang et al. 2021, eqs. 10-12), kept as
// its two factors Z = −Wᵀ G: W = K⁻¹ (√c A)ᵀ (3#V by #C, dense: #C solves with K) and G = ∂f/∂s (3#V by
// 6#T, sparse: 72 entries a tet). Z itself is dense and about 2#T/#V times larger than W: 450 rows on a
// 39,000-tet template are 840 MB as Z, 100 MB as W and 34 MB as G. A product through the factors costs
// #C·3#V + nnz(G) operations instead of #C·6#T.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace vesalius::fit {

class ConstraintJacobian {
 public:
  // Z = −Wᵀ G for Wt = Wᵀ (#C by n) and G (n by p).
  ConstraintJacobian(Eigen::MatrixXd Wt, Eigen::SparseMatrix<double> G);
  // Z as a matrix (#C by p): for few columns, as in a constant-strain stage's six, and for checks.
  explicit ConstraintJacobian(const Eigen::MatrixXd& Z);

  Eigen::Index rows() const { return Wt_.rows(); }
  Eigen::Index cols() const { return G_.cols(); }

  // Z y for y: cols() by K. Returns rows() by K.
  Eigen::MatrixXd operator*(const Eigen::Ref<const Eigen::MatrixXd>& y) const;
  // Zᵀ x for x: rows() by K. Returns cols() by K.
  Eigen::MatrixXd transposeTimes(const Eigen::Ref<const Eigen::MatrixXd>& x) const;
  // Column j of Z (rows() entries) into `out`, from the few columns of Wᵀ that G's column j touches.
  void column(Eigen::Index j, Eigen::Ref<Eigen::VectorXd> out) const;
  // ||Z||², the squared Frobenius norm: one pass over Z's columns, never all held at once.
  double squaredNorm() const;

 private:
  Eigen::MatrixXd Wt_;
  Eigen::SparseMatrix<double> G_;  // column-major: column j lists the rows of Wᵀ that make Z's column j
};

}  // namespace vesalius::fit
