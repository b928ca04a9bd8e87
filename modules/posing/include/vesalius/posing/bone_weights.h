// Bone weights of a tet mesh by Laplace diffusion from the labelled bone vertices (Sujar et al. 2018, §3.3, eqs. 2-5).
//
// For each bone j, W_j solves ∇²W_j = 0 (eq. 4) with W_j = 1 on bone j's vertices and 0 on every other
// bone's vertices, discretised with linear (P1) finite elements: A is the stiffness ("cotangent") matrix
// K_ab = Σ_t vol_t ∇φ_a·∇φ_b restricted to the free vertices, which is symmetric positive definite once
// every free vertex is connected to some bone (eq. 5). A is the same for every bone, so it is factored
// once and all bones are solved as the columns of one right-hand side.
//
// Sujar et al. 2018 argues W ∈ [0, 1] and Σ_j W_j = 1 from the maximum principle (eqs. 2-3). The rows sum to 1
// exactly in the discrete solution too (the constant is in the kernel of K), but the discrete maximum
// principle is only guaranteed when no tet has an obtuse dihedral angle: obtuse tets give positive
// off-diagonal entries of K, and the weights can leave [0, 1] near them (a lone free vertex across a 147°
// dihedral angle from a bone takes cos 147° = -0.84; on a TetGen quality mesh of a body with three bones
// the tests measure no excursion at all). By default the weights are clamped to [0, 1] and each row is
// rescaled to sum to 1 (options.clampAndNormalize), which changes nothing where the principle holds.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace vesalius::posing {

struct BoneWeightsOptions {
  // Clamp weights to [0, 1] and rescale each row to sum 1 (see above); off returns the raw FEM solution,
  // which is how one measures the excursion on a given mesh.
  bool clampAndNormalize = true;
};

// The P1 stiffness ("cotangent") matrix K_ab = Σ_t vol_t ∇φ_a·∇φ_b of eq. 5, #V by #V, both triangles stored.
// Also the Dirichlet energy uᵀKu = ∫|∇u|² of a P1 field u (volume_restoration.h). Throws BadInput if a tet
// is flat or inverted.
Eigen::SparseMatrix<double> stiffnessMatrix(const MatrixX3d& V, const MatrixX4i& T);

// V: #V by 3 rest positions, T: #T by 4 positively oriented tets, boneOfVertex: #V, -1 for free tissue
// and j >= 0 for a vertex inside bone j. Returns W: #V by #B (#B = largest bone index + 1), W(i, j) the
// influence of bone j on vertex i. Throws BadInput if a tet is flat or inverted, an index is out of range,
// there is no bone, a bone index in 0..#B-1 has no vertex, or a free vertex is in no part of the mesh that
// touches a bone (there the weights are undefined); UsageError if boneOfVertex is not #V long.
Eigen::MatrixXd computeBoneWeights(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                                   const BoneWeightsOptions& options = {});

}  // namespace vesalius::posing
