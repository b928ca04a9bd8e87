// The plastic elastic energy of a whole tet mesh, E(s, x) = Σ_t |Fp_t| V0_t ψ(F_t Fp_t⁻¹) (Wang et al. 2021, §3.2,
// eq. 1), with its force, tangent stiffness and the derivative of the force in the plastic strains
// (Appendix B), assembled over tets in parallel.
//
// Shapes: x is 3#V (x0, y0, z0, x1, ...), the deformed vertex positions in mm; s is 6#T, tet-major
// (s.segment<6>(6 t) parameterizes Fp of tet t, eq. 2). Energy is in (unit of μ) · mm³.
// A solver class: the rest geometry and the stiffness sparsity pattern are computed once.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/fem/plastic_tet.h"

#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace vesalius {

class PlasticFem {
 public:
  // restV: #V by 3 template positions; T: #T by 4 tets, positively oriented. Throws BadInput on no tets,
  // bad indices, inverted or flat tets, or μ, λ not positive.
  PlasticFem(const MatrixX3d& restV, const MatrixX4i& T, StableNeoHookean material);

  int vertexCount() const { return vertexCount_; }
  int tetCount() const { return int(T_.rows()); }
  const MatrixX4i& tets() const { return T_; }
  const StableNeoHookean& material() const { return material_; }
  const Eigen::VectorXd& restVolumes() const { return restVolumes_; }  // #T template volumes V0, mm³

  double energy(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const;
  Eigen::VectorXd gradient(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const;  // ∂E/∂x, 3#V
  // ∂²E/∂x², 3#V by 3#V, both triangles stored. The pattern (every tet's 12x12 block plus the whole
  // diagonal) is the same on every call, so SparseCholesky keeps its analysis. projected: PSD.
  Eigen::SparseMatrix<double> stiffness(const Eigen::VectorXd& x, const Eigen::VectorXd& s, bool projected) const;
  // ∂²E/∂x∂s, 3#V by 6#T: Wang et al.'s ∂f_e/∂s (its f_e is ∂E/∂x), column 6 t + i for s_i of tet t.
  Eigen::SparseMatrix<double> plasticForceJacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const;
  // #T values det(F Fp⁻¹); a tet is inverted relative to its plastic rest shape where it is ≤ 0.
  Eigen::VectorXd elasticJacobians(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const;

  // #V by 3 <-> 3#V, row-major (x0, y0, z0, x1, ...).
  static Eigen::VectorXd flatten(const MatrixX3d& V);
  static MatrixX3d unflatten(const Eigen::VectorXd& x);

 private:
  void buildStiffnessPattern();
  Eigen::Matrix<double, 4, 3> corners(const Eigen::VectorXd& x, int t) const;
  void checkSizes(const Eigen::VectorXd& x, const Eigen::VectorXd& s) const;
  template <class PerTet>
  auto perTet(const Eigen::VectorXd& x, const Eigen::VectorXd& s, const PlasticTetBlocks& blocks,
              PerTet keep) const;

  int vertexCount_;
  MatrixX4i T_;
  StableNeoHookean material_;
  std::vector<PlasticTetRest> rest_;
  Eigen::VectorXd restVolumes_;
  Eigen::SparseMatrix<double> pattern_;  // stiffness pattern, zero values
  // For tet t, corner pair (a, b) and column l of the 3x3 block: where row 3 T(t, a) of column
  // 3 T(t, b) + l sits in pattern_'s value array (the block's 3 rows follow it).
  std::vector<std::array<int, 48>> blockStart_;
};

}  // namespace vesalius
