// Dual quaternion skinning of a tet mesh's vertices (Sujar et al. 2018, §3.5; Kavan, Collins, Žára, O'Sullivan,
// "Geometric skinning with approximate dual quaternion blending", ACM TOG 27(4), 2008).
//
// Each bone transform becomes a unit dual quaternion q̂_j = q_j + ε ½ t_j q_j; a vertex takes the
// normalised blend Σ_j w_j q̂_j, a rigid motion, so joints do not collapse as in LBS. Before blending,
// each q̂_j is negated if needed to lie in the hemisphere of the heaviest bone's q (antipodality).
// Bent joints bulge instead, which Sujar et al. 2018 reports as volume gain (§5, Fig. 7). Measured as the signed
// volume of the posed tets it is none when the joint's axis passes through the centroid of the limb's
// cross-section: every vertex turns rigidly about that axis (tests/posing/skinning_test.cpp says why).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <vector>

namespace vesalius::posing {

// V: #V by 3 rest positions, W: #V by #B bone weights, transforms: #B bone transforms from rest to posed.
// Returns #V by 3 posed positions. Throws UsageError if the sizes disagree or there are vertices but no bones.
MatrixX3d dualQuaternionSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                                 const std::vector<Eigen::Isometry3d>& transforms);
// The same into `posed` (resized to #V by 3; not V itself), which a caller posing many frames keeps.
void dualQuaternionSkinning(const MatrixX3d& V, const Eigen::MatrixXd& W,
                            const std::vector<Eigen::Isometry3d>& transforms, MatrixX3d& posed);

}  // namespace vesalius::posing
