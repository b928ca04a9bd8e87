// The long axis of a bone from its points: the eigenvector of the largest eigenvalue of their covariance
// (principal component analysis), one of the two directions Sujar et al. 2018, §3.1, estimates per bone
// (bone_frame.h makes the frame), with the checks a bone frame needs (core/principal_axes.h computes it).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::posing {

// P: #P by 3 points. Returns the unit principal axis, signed so that its dot product with `towards` is
// not negative. Throws BadInput if P has fewer than two distinct points or no single largest
// eigenvalue (the two largest within 1e-9 of each other, relative: a ball or a disc has no long axis).
Eigen::Vector3d principalAxis(const MatrixX3d& P, const Eigen::Vector3d& towards);

}  // namespace vesalius::posing
