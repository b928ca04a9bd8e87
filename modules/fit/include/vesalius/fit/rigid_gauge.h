// Stabilisation of un-attached objects (Wang et al. 2021, §3.6, eqs. 19-20). Without attachments an equilibrium
// is defined only up to a rigid motion (Nullspace Lemma), so the pose is fixed by two constraints on the
// set D of constrained surface points (weights 1/|D|, material positions X_j in the template):
//   centroid:  Σ w_j x_j − Σ w_j X_j = t                                   (19)
//   rotation:  Polar(Σ w_j (x_j − t)(X_j − X̄)ᵀ) = R                         (20)
// Any rigid motion of an equilibrium is an equilibrium, so imposing the gauge on a solved equilibrium is
// exact. Its linearisation (translation rows, and the rotation's angular rows through the derivative of
// Polar, §3.7) turns the pinned Jacobian into the gauge's one (equilibrium_jacobian.h).
#pragma once

#include "vesalius/fit/point_constraints.h"

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::fit {

class RigidGauge {
 public:
  // D: the constrained points (their vertices and weights); restV: #V by 3 template. t and R are those of
  // positions x (3#V), i.e. x satisfies the gauge.
  RigidGauge(const std::vector<PointConstraint>& D, const MatrixX3d& restV, const Eigen::VectorXd& x);

  // x moved rigidly so that it satisfies (19) and (20).
  Eigen::VectorXd impose(const Eigen::VectorXd& x) const;

  // The linearised constraints at x: 6 by 3#V, rows d(centroid) (3) and the rotation's angular velocity
  // ω with [ω]× = Rᵀ dR (3).
  Eigen::MatrixXd constraintJacobian(const Eigen::VectorXd& x) const;

 private:
  Eigen::Vector3d centroid(const Eigen::VectorXd& x) const;
  Eigen::Matrix3d covariance(const Eigen::VectorXd& x) const;

  std::vector<PointConstraint> D_;
  MatrixX3d X_;           // #D material positions, centred on X̄
  Eigen::Vector3d Xbar_;  // material centroid
  Eigen::Vector3d t_;
  Eigen::Matrix3d R_;
};

// The six rigid motions of positions x (3#V): 3#V by 6, translations then rotations about the centroid
// (the nullspace of the tangent stiffness at an equilibrium, Wang et al. 2021, Nullspace Lemma).
Eigen::MatrixXd rigidModes(const Eigen::VectorXd& x);

}  // namespace vesalius::fit
