// Bounded biharmonic weights of handles on a voxel grid (Jacobson, Baran, Popović, Sorkine, "Bounded
// biharmonic weights for real-time deformation", SIGGRAPH 2011, §3 Eq. 1–4), as the fat editor of
// Dicko et al. 2013, §6, uses them: "We set the bones as boundary constraints and minimize biharmonic (Laplacian)
// energy subject to these constraints ... we compute bounded biharmonic weights using a regular voxel
// grid" (after Kavan and Sorkine 2012).
//
// Per handle j, over the domain voxels:
//   minimise ½ Σ_voxels (L w_j)²   subject to  w_j = 1 on handle j, w_j = 0 on the other handles,
//                                               0 <= w_j <= 1 elsewhere,
// L the graph Laplacian of the domain's 6-neighbourhood, (L w)_v = Σ_n c_a (w_n − w_v), c_a =
// (s_min / s_a)² for a neighbour along axis a (spacing s), natural (Neumann) boundary at the domain's
// surface. The voxels all have one volume, so the lumped mass of A = L M⁻¹ L is a constant factor and
// the energy is ½ wᵀ L² w. Like the BBW paper (§3, "we optimize each weight function separately and
// then normalize"), each handle is solved alone and the partition of unity is made by dividing every
// voxel's weights by their sum afterwards; `maxSumDeviation` says how far the sums were from 1.
//
// The QP: K = A restricted to the free voxels (every non-handle voxel; one matrix for all handles, only
// the right-hand side differs). Start: the unconstrained biharmonic weights (one factorization of K,
// one block solve). Then the primal-dual active set method (Hintermüller, Ito, Kunisch, "The
// primal-dual active set strategy as a semismooth Newton method", SIAM J. Optim. 13(3), 2003): free
// voxels whose weight left [0, 1] are held at the bound they crossed, held voxels whose multiplier (the
// gradient g = K w − b) has the wrong sign are released, and the weights are solved again with the held
// ones fixed (numeric Cholesky, linalg/sparse_cholesky.h, the analysis reused: held rows become identity
// rows in the same pattern), until the sets repeat; then w and g satisfy the KKT conditions to round-off.
// Measured: 9 iterations on the two-box bar of tests/fat (of 4,720 free voxels 996 end at 0, 448 at 1),
// 1–6 per bone group on the full-body reference at 20 mm voxels, 1–15 at 10 mm. The method converges finitely for M-matrices; K = L² is not
// one and the method may cycle, so if a pair of sets comes back (or maxActiveSetIterations pass) the
// last iterate, clamped, starts Bertsekas' projected Newton method ("Projected Newton methods for
// optimization problems with simple constraints", SIAM J. Control Optim. 20(2), 1982), which decreases
// the objective at every step and converges (Prop. 2; the full Newton step lands on the minimiser once
// the ε-binding set is the active set): Newton steps on the non-binding voxels, diagonally scaled
// gradient steps on the binding ones, Armijo search along the projection arc P[w + α d]. Both stop when
// the KKT residual max_v |w_v − P[w_v − g_v]| (0 exactly at the solution: g = 0 where w is inside,
// g >= 0 at 0, g <= 0 at 1) is at most `tolerance`; NumericalFailure after maxIterations.
//
// Free voxels in a connected part of the domain with no handle have no defined weights; they get none
// (row −1) and are counted. Handles are solved in parallel (TBB, each with its own factorization); the
// result does not depend on the number of threads.
#pragma once

#include "vesalius/core/grid.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace vesalius::fat {

struct BoundedBiharmonicOptions {
  double tolerance = 1e-10;      // on the KKT residual (weights are in [0, 1])
  int maxActiveSetIterations = 50;  // per handle, before falling back to projected Newton
  int maxIterations = 500;       // projected Newton iterations per handle
  double bindingEpsilon = 1e-3;  // ε of the binding set
  double armijo = 1e-4;          // sufficient decrease along the projection arc
};

struct BoundedBiharmonicWeights {
  GridGeometry geometry;
  std::vector<std::int32_t> row;  // per grid voxel (linear index): its row of W, −1 if it has none
  std::vector<std::int64_t> voxel;  // #N: the grid voxel of each row, ascending
  Eigen::MatrixXd W;    // #N by #handles, normalised: rows sum to 1
  Eigen::MatrixXd raw;  // #N by #handles, each column the QP's solution before normalising
  std::vector<int> iterations;               // #handles: factorizations (active set + projected Newton)
  std::vector<char> projectedNewton;         // #handles: 1 where the active set method cycled
  std::vector<double> kktResidual;           // #handles, at the end
  std::vector<std::int64_t> atZero, atOne;   // #handles: free voxels at each bound
  std::int64_t freeVoxels = 0;               // in W, not on a handle
  std::int64_t unreachable = 0;              // domain voxels left out: no handle in their part
  double maxSumDeviation = 0;                // max over rows of |Σ_j raw − 1|
};

// labels: −1 outside the domain, 0 for a free domain voxel, j + 1 on handle j (0 <= j < handleCount).
// Throws UsageError for handleCount < 1, a label outside −1..handleCount, a handle with no voxel, or
// bad options; NumericalFailure if the QP does not converge.
BoundedBiharmonicWeights boundedBiharmonicWeights(const Grid<std::int32_t>& labels, int handleCount,
                                                  const BoundedBiharmonicOptions& options = {});

}  // namespace vesalius::fat
