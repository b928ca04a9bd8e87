// Optimized centres of rotation of a tet mesh's vertices, the precomputation of CoR skinning (Le & Hodgins,
// "Real-time skeletal skinning with optimized centers of rotation", ACM TOG 35(4), 2016; Sujar et al. 2018, §3.5,
// eqs. 6-7, which recasts their surface integral over tets).
//
// A vertex p should rotate like the parts of the body whose weights resemble its own. Its centre is
//   cor_p = Σ_t s(w_p, w_t) V_t c_t / Σ_t s(w_p, w_t) V_t                                   (eq. 7)
// over tets t with volume V_t, centroid c_t and w_t the mean of its corners' weights, and
//   s(w_p, w_t) = Σ_{j<k} w_pj w_pk w_tj w_tk exp(-(w_pj w_tk - w_pk w_tj)² / σ²)          (eq. 6)
// (Sujar et al. 2018 sums over j ≠ k, twice the same terms; the factor cancels in eq. 7).
//
// Two ways to evaluate the sums:
// - computeRotationCentersBruteForce: every vertex against every tet, O(#V #T #pairs); the reference.
// - computeRotationCenters: eq. 6 is a sum over bone pairs, and a pair's term depends on the tet only through
//   b_t = (w_tj, w_tk). So, for each bone pair (j, k) some vertex uses, the tets with w_tj w_tk > 0 are grouped
//   by b_t snapped to a grid of square cells of width `clusterWidth` in the (w_j, w_k) plane, and a vertex
//   visits only the groups of its own pairs: O(#V × pairs per vertex × groups per pair), instead of
//   O(#V × groups of the full #B-dimensional weight vectors), which do not merge anything with many bones.
//   Approximation: within a group, the factor w_tj w_tk V_t of eq. 6 is summed exactly (with c_t for the
//   numerator) and only the kernel exp(-(w_pj w_tk - w_pk w_tj)²/σ²) is Taylor expanded about the group's
//   mean b̄, to second order in b_t - b̄ (first order for its correlation with c_t; rotation_centers.cpp).
//   Measured against brute force, as fractions of the bounding-box diagonal, at the default width 1/16:
//   the four-bone bar of the tests 1.2e-4 (every vertex); a 32-bone chain, 43 bone pairs per vertex,
//   1.4e-5 (sampled; tests/posing/rotation_centers_test.cpp); MakeHuman's body rig (19k vertices, 74k tets,
//   50 bones; Laplace weights are dense: ~25 bones per vertex above 10⁻⁶ of its largest, ~180 pairs)
//   3.1e-5 = 0.06 mm (worst of 100 sampled vertices) in 3.4 s on one core, where brute force takes ~1 h
//   and the former grouping by the full weight vector had not finished after 6.6 CPU-minutes. The width
//   trades time for accuracy: on the body (30 sampled vertices) 1.0e-6, 6.2e-6, 2.7e-5, 1.1e-4 of the
//   diagonal at 1/64, 1/32, 1/16, 1/8, in 13, 6.7, 3.6, 2.0 s. Benchmarks: tests/bench/bench_posing.cpp.
// Both are parallel over vertices (TBB; the grouping over pairs), each sum in a fixed order, so the result
// does not depend on the thread count. Both skip the bone pairs (j, k) whose product w_pj w_pk is below
// 10⁻⁶ of the vertex's largest, which cannot move the centre measurably. A vertex for which s vanishes on
// every tet (it follows one bone only: all products w_pj w_pk are 0) has no centre; it gets its own
// position, with which CoR skinning reduces to linear blend skinning, as Le & Hodgins prescribe for it.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::posing {

struct RotationCenterOptions {
  double sigma = 0.1;              // kernel width σ of eq. 6 (Le & Hodgins' value; Sujar et al. 2018 uses σ < 0.1)
  double clusterWidth = 1.0 / 16;  // edge of a bone pair's cells grouping tets, in [1/1024, 1] (clustered only)
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
