// Least-squares similarity (or rigid) transform between paired points (Umeyama, "Least-squares
// estimation of transformation parameters between two point patterns", IEEE PAMI 13(4), 1991).
// The fit uses it for the initial placement of a template (Wang et al.'s Fig. 1 starts from a rigidly aligned
// template) and for the rotation-translation step of the un-attached block-coordinate descent (§3.6); the
// transfer for the rigid and similarity steps of its registrations.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius {

struct SimilarityTransform {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // det +1
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return scale * rotation * p + translation; }
  MatrixX3d apply(const MatrixX3d& P) const;
};

// The transform T minimising Σ w_i ||T(from_i) − to_i||². from, to: #P by 3; weights: #P (empty means all
// 1). allowScale false gives the rigid transform. Throws BadInput when fewer than 3 points or all
// points are (nearly) collinear.
SimilarityTransform fitSimilarity(const MatrixX3d& from, const MatrixX3d& to, const Eigen::VectorXd& weights,
                                  bool allowScale);

}  // namespace vesalius
