// A bone's local frame from two directions (Sujar et al. 2018, §3.1: "We estimate two orthogonal vectors and the
// bone rotation centre from a set of annotated vertices. The third vector of the basis is calculated as
// the cross product of the first two vectors").
//
// The two estimated directions are rarely exactly orthogonal, so the first is kept and the second is made
// orthogonal to it (Gram–Schmidt); the third is their cross product, ordered so that the frame is
// right-handed. Which axis each direction becomes is the caller's: e.g. a femur's long axis is its z
// (superior at rest) and the line through the hip centres its x (left), as LPS and joint_angles.h have it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace vesalius::posing {

// firstAxis, secondAxis: distinct column indices 0..2 (x, y, z). Returns a rotation (columns: the frame's
// x, y, z axes in world coordinates) whose column firstAxis is first normalised and whose column
// secondAxis lies in the plane of first and second, on second's side. Throws UsageError for equal or
// out-of-range axes, BadInput if a direction is zero or the two are parallel (within 1e-9 rad).
Eigen::Matrix3d boneFrame(int firstAxis, const Eigen::Vector3d& first, int secondAxis, const Eigen::Vector3d& second);

// A joint's rest transform: the frame `axes` (a rotation) placed at `origin`.
Eigen::Isometry3d placedFrame(const Eigen::Matrix3d& axes, const Eigen::Vector3d& origin);

}  // namespace vesalius::posing
