// The plastic strain Laplacian L and the invertible "base" matrix B = L² − Σ ψᵢψᵢᵀ of the Woodbury
// search-direction solve (Wang et al. 2021, Appendix A, eqs. 28-30; §3.4, eq. 13; §3.5, Singular Lemma (iii)).
//
// Plastic strains s are 6#T long and TET-MAJOR: s.segment<6>(6 t) = (s1..s6) of tet t, the entries
// (xx, xy, xz, yy, yz, zz) of the symmetric plastic deformation gradient. L applies the tet Laplacian Lsc
// to each component c, weighted by ξ_c = (1, √2, √2, 1, √2, 1) because the off-diagonal components
// stand for two entries of Fp (eq. 29).
#pragma once

#include "vesalius/fit/constraint_jacobian.h"

#include "vesalius/core/mesh.h"
#include "vesalius/linalg/sparse_cholesky.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>

namespace vesalius::fit {

// ξ_c of eq. 29.
extern const std::array<double, 6> kPlasticStrainWeights;

// Lsc of eq. 28: #T by #T, tets adjacent when they share a face. Throws BadInput on negative vertex
// indices or on a face shared by more than two tets.
Eigen::SparseMatrix<double> tetAdjacencyLaplacian(const MatrixX4i& T);

// L s for s of length 6#T (tet-major); Lsc: #T by #T from tetAdjacencyLaplacian.
Eigen::VectorXd applyPlasticLaplacian(const Eigen::SparseMatrix<double>& Lsc, const Eigen::VectorXd& s);

// 6#T by 6, orthonormal: column c is 1/√#T on component c of every tet, the nullspace of L for a
// face-connected mesh.
Eigen::MatrixXd plasticLaplacianNullspace(Eigen::Index tetCount);

// Applies B⁻¹ for B = L² − Σᵢ ψᵢψᵢᵀ (eq. 13) without forming B or the rank-6 term. By the Singular
// Lemma (iii) with αᵢ = −1, B⁻¹h = (L²)⁺h − Σᵢ (ψᵢᵀh) ψᵢ, and since L² = diag(ξ_c²) ⊗ Lsc² acts per
// component, (L²)⁺ = diag(1/ξ_c²) ⊗ (Lsc⁺)². Lsc⁺ is applied through one sparse Cholesky factorization
// of Lsc with tet 0 grounded (row and column removed), followed by removing the mean. Calls on one
// solver must not run concurrently: CHOLMOD keeps its workspace in the factorization.
class SmoothnessBaseSolver {
 public:
  // Lsc: #T by #T from tetAdjacencyLaplacian. Factors once. Throws BadInput if the mesh is empty or not
  // face-connected (L would have a nullspace larger than the six ψᵢ).
  explicit SmoothnessBaseSolver(const Eigen::SparseMatrix<double>& Lsc);

  Eigen::Index tetCount() const { return tetCount_; }
  const Eigen::SparseMatrix<double>& laplacian() const { return Lsc_; }

  // h: 6#T by K, tet-major columns. Returns B⁻¹h (6#T by K) for B = a L² − Σ ψᵢψᵢᵀ (a = smoothnessScale,
  // 1 in eq. 13; the damped search direction scales L²), with two sparse solves on 6K columns.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& h, double smoothnessScale = 1.0) const;

  // Z: #C by 6#T (columns tet-major), Zpsi: Z ψ (#C by 6). Returns Z (L²)⁺ Zᵀ (#C by #C) with one sparse
  // solve on 6#C columns: Z (L²)⁺ Zᵀ = Gᵀ G for G = L⁺ Zᵀ, so neither Z nor (L²)⁺ Zᵀ is formed whole.
  // Z B⁻¹ Zᵀ is this minus (Zψ)(Zψ)ᵀ.
  Eigen::MatrixXd sandwich(const ConstraintJacobian& Z, const Eigen::MatrixXd& Zpsi) const;

 private:
  // Lsc⁺ on the component-major block X (#T − 1 by n, row-major, rows in the grounded factor's order),
  // whose columns have zero mean; in place. Returns the mean removed after the solve (minus row 0 of
  // Lsc⁺ X).
  Eigen::RowVectorXd applyScalarPseudoInverse(RowMajorMatrixXd& X) const;

  Eigen::Index tetCount_;
  Eigen::SparseMatrix<double> Lsc_;
  // Of Lsc without row and column 0; nested dissection, since sandwich solves 6#C columns with it.
  SparseCholesky groundedCholesky_{FillReducingOrdering::nestedDissection};
  Eigen::VectorXi groundedOrder_;  // the tet (1 .. #T − 1) at each row of that factor's order
};

}  // namespace vesalius::fit
