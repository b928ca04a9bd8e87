// Skeleton poses as skinning consumes them.
//
// A pose is the posed world transform of every joint (#joints, the form of Motion::worldPose). Skinning
// (linear_blend_skinning.h and the others) takes instead, per bone, the rigid map from the rest body to
// the posed body: posedWorld_j · restWorld_j⁻¹.
//
// Motion files and rigs come in their authors' axes and units; io/body_axes.h moves them into LPS mm.
#pragma once

#include "vesalius/core/skeleton.h"

#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

// posedWorld: #joints posed world transforms. Returns the #joints skinning transforms
// posedWorld_j · restWorld_j⁻¹. Throws UsageError if the sizes disagree.
std::vector<Eigen::Isometry3d> restToPosed(const Skeleton& skeleton, const std::vector<Eigen::Isometry3d>& posedWorld);

}  // namespace vesalius::posing
