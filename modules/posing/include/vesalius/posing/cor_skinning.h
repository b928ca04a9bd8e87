// Skinning with optimized centres of rotation, the interactive step (Le & Hodgins, "Real-time skeletal
// skinning with optimized centers of rotation", ACM TOG 35(4), 2016; Sujar et al. 2018, §3.5, "used in the
// interactive step as it is shown in [11]").
//
// Vertex i with weights w_i and centre p_i (rotation_centers.h) takes
//   R = rotation of q / |q|, q = Σ_j w_ij q_j (bone rotations as quaternions, each in the hemisphere of
//       the heaviest bone's, as in DQS),
//   t = Σ_j w_ij T_j p_i − R p_i  (where linear blend skinning takes the centre, less its rotation),
//   v' = R v + t.
// Rotations blend as in DQS (no collapse), while the centre, which lies between the bones the vertex
// follows, keeps the bulge of DQS away. With p_i = v_i this is linear blend skinning, which is what a
// vertex without a centre gets. Computed as v' = R (v − p_i) + Σ_j w_ij T_j p_i, the same up to rounding.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

// V: #V by 3 rest positions, W: #V by #B bone weights, centres: #V by 3 from computeRotationCenters,
// transforms: #B bone transforms from rest to posed. Returns #V by 3 posed positions. Throws UsageError if
// the sizes disagree or there are vertices but no bones.
MatrixX3d corSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W, const MatrixX3d& centres,
                      const std::vector<Eigen::Isometry3d>& transforms);
// The same into `posed` (resized to #V by 3; not V itself), which a caller posing many frames keeps.
void corSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W, const MatrixX3d& centres,
                 const std::vector<Eigen::Isometry3d>& transforms, MatrixX3d& posed);

}  // namespace vesalius::posing
