// Fixed point constraints as few rows: the attachment terms of Wang et al. 2021, eq. 6 (Appendix F, eqs. 52-53),
//   Σ_k c_k/2 ||A_k x + b_k||²,
// rewritten exactly as ½||R x − q||² + offset with at most 3 rows per template vertex they involve.
//
// Why: every constraint row is a row of Z, and the Woodbury solve costs grow with #rows (one Laplacian
// solve per row and a #rows² Gram matrix, §3.4). Wang et al. 2021 attaches each bone vertex of the insertion
// (§4.1.2); a bone surface from a CT has one vertex per millimetre or so, and the gluteus medius on the
// test CT's hip bone takes 1,225 of them, 3,675 rows, for a template whose boundary triangles hold far
// fewer vertices. The attachments' material points and targets never change, so their sum is a fixed
// quadratic in x and can be factored once: with W the #A by #m barycentric weights of the #m vertices
// involved and D = diag(c), the energy is Σ_d ½ (x_dᵀ M x_d − 2 (Wᵀ D t_d)ᵀ x_d + t_dᵀ D t_d) per
// coordinate d, for M = Wᵀ D W = U Λ Uᵀ. R = Λ^½ Uᵀ (per coordinate) and q_d = Λ^-½ Uᵀ Wᵀ D t_d give the
// same energy, gradient and Gauss-Newton Hessian. Eigenvalues below 1e-12 λ_max are dropped (their
// energy is the round-off of the others). When the constraints involve as many vertices as there are
// constraints, nothing is gained and their own rows are returned.
#pragma once

#include "vesalius/fit/point_constraints.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace vesalius::fit {

struct CompressedConstraints {
  Eigen::SparseMatrix<double> rows;  // R: 3#R by 3#V, x stacked (x0, y0, z0, x1, ...)
  Eigen::VectorXd targets;           // q: 3#R
  double offset = 0.0;               // the energy R and q leave out, a constant

  // The same energy as the constraints': ½||R x − q||² + offset.
  double energy(const Eigen::VectorXd& x) const { return 0.5 * residuals(x).squaredNorm() + offset; }
  Eigen::VectorXd residuals(const Eigen::VectorXd& x) const { return rows * x - targets; }
};

// constraints: fixed material points and targets (weights c_k > 0); vertexCount: #V of the mesh.
// An empty list gives no rows and offset 0.
CompressedConstraints compressConstraints(const std::vector<PointConstraint>& constraints, Eigen::Index vertexCount);

}  // namespace vesalius::fit
