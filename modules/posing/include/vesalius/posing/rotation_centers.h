// Optimized centres of rotation of a tet mesh's vertices, the precomputation of CoR skinning (Le & Hodgins,
// "Real-time skeletal skinning with optimized centers of rotation", ACM TOG 35(4), 2016; seed 001 §3.5,
// eqs. 6-7, which recasts their surface integral over tets).
//
// A vertex p should rotate like the parts of the body whose weights resemble its own. Its centre is
//   cor_p = Σ_t s(w_p, w_t) V_t c_t / Σ_t s(w_p, w_t) V_t                                   (eq. 7)
// over tets t with volume V_t, centroid c_t and w_t the mean of its corners' weights, and
//   s(w_p, w_t) = Σ_{j<k} w_pj w_pk w_tj w_tk exp(-(w_pj w_tk - w_pk w_tj)² / σ²)          (eq. 6)
// (the seed sums over j ≠ k, twice the same terms; the factor cancels in eq. 7).
//
// Two ways to evaluate the sums:
// - computeRotationCentersBruteForce: every vertex against every tet, O(#V #T); the reference.
// - computeRotationCenters: tets are first grouped by their weights, snapped to a grid of cells of width
//   `clusterWidth` in weight space. A group enters eq. 7 once, at its volume-weighted mean weight, with its
//   total volume and moment plus a first-order correction for the spread of weights and positions within
//   it (rotation_centers.cpp), so the cost is O(#V #groups). Weights vary smoothly, so the groups are few:
//   on the four-bone bar of the tests, 1/64 gives centres within 2e-4 of the bounding-box diagonal of the
//   brute-force ones, 40 times faster at 18k tets and (sampled) thousands of times at 4M tets
//   (tests/bench/bench_posing.cpp).
// Both are parallel over vertices (TBB) and skip the bone pairs (j, k) whose product w_pj w_pk is below
// 10⁻⁶ of the vertex's largest, which cannot move the centre measurably. A vertex for which s vanishes on
// every tet (it follows one bone only: all products w_pj w_pk are 0) has no centre; it gets its own
// position, with which CoR skinning reduces to linear blend skinning, as Le & Hodgins prescribe for it.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::posing {

struct RotationCenterOptions {
  double sigma = 0.1;              // kernel width σ of eq. 6 (Le & Hodgins' value; the seed uses σ < 0.1)
  double clusterWidth = 1.0 / 64;  // edge of the weight-space cells grouping tets, in [1e-4, 1] (clustered only)
};

// V: #V by 3 rest positions, T: #T by 4 tets, W: #V by #B bone weights. Returns #V by 3 centres of
// rotation. Throws UsageError if W does not have #V rows or an option is out of range, BadInput if a tet
// refers to a missing vertex.
MatrixX3d computeRotationCenters(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W,
                                 const RotationCenterOptions& options = {});

// Same inputs, evaluating eq. 7 tet by tet (clusterWidth is ignored), for the vertices listed in `only`
// (#S indices; every vertex if empty, so that the reference can be sampled on meshes too large for it).
// Returns #S (or #V) by 3 centres. Throws as above, and UsageError if an index in `only` is out of range.
MatrixX3d computeRotationCentersBruteForce(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W,
                                           const RotationCenterOptions& options = {},
                                           const Eigen::VectorXi& only = Eigen::VectorXi());

}  // namespace vesalius::posing
