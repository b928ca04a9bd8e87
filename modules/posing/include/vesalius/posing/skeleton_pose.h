// Skeleton poses as skinning consumes them, and moving a skeleton into Vesalius's space.
//
// A pose is the posed world transform of every joint (#joints, the form of Motion::worldPose). Skinning
// (linear_blend_skinning.h and the others) takes instead, per bone, the rigid map from the rest body to
// the posed body: posedWorld_j · restWorld_j⁻¹.
//
// Motion files and rigs come in their authors' axes and units (BVH and MakeHuman: +Y up, the body facing
// +Z, its left at +X; MakeHuman in decimetres). Inside Vesalius they are millimetres in LPS (DESIGN.md);
// transformSkeleton is the conversion the apps apply at their edge.
#pragma once

#include "vesalius/core/skeleton.h"

#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

// Rotation from +Y-up, +Z-forward, +X-left axes (BVH, MakeHuman) to LPS: L = X, P = −Z, S = Y.
Eigen::Matrix3d yUpToLps();

// The skeleton seen in new axes: every joint's world rest frame R, t becomes axes·R·axesᵀ, scale·axes·t
// (lengths scale, joint frames rotate with the body). `axes` must be a rotation, scale positive; throws
// UsageError otherwise.
Skeleton transformSkeleton(const Skeleton& skeleton, const Eigen::Matrix3d& axes, double scale);

// posedWorld: #joints posed world transforms. Returns the #joints skinning transforms
// posedWorld_j · restWorld_j⁻¹. Throws UsageError if the sizes disagree.
std::vector<Eigen::Isometry3d> restToPosed(const Skeleton& skeleton, const std::vector<Eigen::Isometry3d>& posedWorld);

}  // namespace vesalius::posing
