// Linear blend skinning of a tet mesh's vertices (Sujar et al. 2018, §3.5; Magnenat-Thalmann et al. 1988):
// v' = Σ_j w_j T_j v. Fast, but blending rotation matrices linearly shrinks the mesh near bent or
// twisted joints (volume loss, "candy wrapper"), the baseline the other methods are measured against.
// Computed as Σ_j w_j (T_j v), the same up to rounding.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

// V: #V by 3 rest positions, W: #V by #B bone weights (rows summing to 1), transforms: #B bone transforms
// from rest to posed. Returns #V by 3 posed positions. Throws UsageError if the sizes disagree or there are
// vertices but no bones.
MatrixX3d linearBlendSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                              const std::vector<Eigen::Isometry3d>& transforms);
// The same into `posed` (resized to #V by 3; not V itself), which a caller posing many frames keeps: no
// allocation then.
void linearBlendSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                         const std::vector<Eigen::Isometry3d>& transforms, MatrixX3d& posed);

}  // namespace vesalius::posing
