// Principal component analysis of points: their centroid and the eigenvectors of their covariance, the
// longest axis first. One function for the template placement (fit), the bones' long axes (posing) and
// the bone checks and digit joints (transfer).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius {

struct PrincipalAxes {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();   // columns: unit axes, largest variance first; det +1
  Eigen::Vector3d variances = Eigen::Vector3d::Zero();  // along each axis (units of P squared), decreasing
};

// P: #P by 3 points. Throws BadInput if P has no row.
PrincipalAxes principalAxes(const MatrixX3d& P);

}  // namespace vesalius
