// The point terms of the fitting objective (Wang et al. 2021, eq. 6 and Appendix F, eqs. 52-53):
//   Σ_k c_k/2 ||A_k x + b_k||²,  A_k = [w1 I3  w2 I3  w3 I3  w4 I3] S_k,  b_k = −target_k,
// one per landmark, ICP marker and attachment. A constrained point is a material point: a tet and
// barycentric weights of its corners (a boundary triangle's point has weight 0 at the fourth corner), so
// landmarks, attachments and the closest points of ICP markers share one representation, which also
// serves as a spring of the equilibrium (fem/point_springs.h).
#pragma once

#include "vesalius/fem/point_springs.h"

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <vector>

namespace vesalius::fit {

struct PointConstraint {
  int tet = 0;
  std::array<int, 4> vertices{0, 0, 0, 0};            // T(tet, 0..3)
  Eigen::Vector4d weights = Eigen::Vector4d::Zero();  // sum to 1
  Eigen::Vector3d target = Eigen::Vector3d::Zero();   // world position, mm
  double weight = 1.0;                                // c_k
};

// The constrained point Σ w_i x_{v_i}; x is 3#V stacked (x0, y0, z0, x1, ...).
Eigen::Vector3d constrainedPoint(const PointConstraint& c, const Eigen::VectorXd& x);

// The rows √c_k A_k of all constraints: 3#C by 3#V.
Eigen::SparseMatrix<double> constraintRows(const std::vector<PointConstraint>& constraints,
                                           Eigen::Index vertexCount);

// √c_k (A_k x + b_k) for all constraints: 3#C. Half its squared norm is the constraints' energy.
Eigen::VectorXd constraintResiduals(const std::vector<PointConstraint>& constraints, const Eigen::VectorXd& x);

// Material points of a tet mesh (#P by 3 points in the rest positions restV) as constraints towards
// `targets` (#P by 3) with weight c: each point takes the tet that holds it, or the nearest tet if it
// lies outside (clamped barycentric coordinates), as Wang et al. 2021, §4.1.2, embeds attachment points.
std::vector<PointConstraint> embedMaterialPoints(const MatrixX3d& restV, const MatrixX4i& T,
                                                 const MatrixX3d& points, const MatrixX3d& targets, double c);

// The same points as springs of stiffness k in the elastic equilibrium (attachments, §3.3; and the
// markers of the elastic baseline).
PointSprings asSprings(const std::vector<PointConstraint>& constraints, double k);

}  // namespace vesalius::fit
