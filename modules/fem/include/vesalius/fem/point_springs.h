// Soft attachments: zero-rest-length springs pulling material points of the tet mesh to world targets
// (the attachment force f_a of Wang et al. 2021, §3.3, written as in Appendix F, eqs. 52-53):
//   E_a(x) = Σ_i k_i/2 ||Σ_c w_ic x_{T(tet_i, c)} − target_i||².
// Quadratic in x, so the Hessian is constant. A vertex is the material point with weight 1 on one corner.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/SparseCore>

#include <vector>

namespace vesalius {

struct MaterialPoint {
  int tet = 0;
  Eigen::Vector4d barycentric = Eigen::Vector4d(1, 0, 0, 0);  // weights of the tet's 4 corners
};

struct PointSprings {
  std::vector<MaterialPoint> points;
  MatrixX3d targets;          // #points by 3, mm
  Eigen::VectorXd stiffness;  // #points spring constants k ≥ 0, (unit of μ) · mm
};

// x: 3#V deformed positions; T: #T by 4. All throw BadInput if the springs do not fit T or each other.
double pointSpringEnergy(const PointSprings& springs, const MatrixX4i& T, const Eigen::VectorXd& x);
Eigen::VectorXd pointSpringGradient(const PointSprings& springs, const MatrixX4i& T, const Eigen::VectorXd& x);
// 3#V by 3#V, both triangles; its pattern lies inside the tets' 12x12 blocks (PlasticFem::stiffness).
Eigen::SparseMatrix<double> pointSpringHessian(const PointSprings& springs, const MatrixX4i& T, int vertexCount);

}  // namespace vesalius
