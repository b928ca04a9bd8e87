// The fat editor's thickness (Dicko et al. 2013, §6): "The editor computes linear combination of pre-computed bone
// weights with the control parameters set by the users to generate the final fat distribution map",
// e.g. "0.4 to the pelvis and sacrum bones ... 0 to the skull because there is no fat beneath his scalp".
//
//   thickness(x) = maxThicknessMm · Σ_j w_j(x) · amount_j
//
// with w_j the normalised bounded biharmonic weights of bone j (bounded_biharmonic_weights.h) at x.
// Dicko et al. 2013 gives the amounts no unit (its Fig. 3 shows brightness); here an amount is the fraction of
// maxThicknessMm, so 0.4 with the default 50 mm is 20 mm of fat where the pelvis alone has weight (the
// test CT's subcutaneous fat has a median of 18 mm and a 95th percentile of 45 mm,
// docs/methods/fat-thickness.md). Amounts are not limited to [0, 1]; thickness is linear in them.
//
// Weights at a point x (a skin vertex lies on the domain's surface, between voxel centres): trilinear
// over the eight voxel centres around x, using only those with weights and renormalising their
// trilinear factors; where none of the eight has weights (a finger thinner than a voxel), the weights of
// the nearest voxel centre that has them.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/fat/bounded_biharmonic_weights.h"

#include <Eigen/Core>

namespace vesalius::fat {

struct BoneFatOptions {
  double maxThicknessMm = 50;  // the thickness an amount of 1 gives
};

struct BoneFatThickness {
  Eigen::VectorXd thickness;  // #P, mm
  Eigen::MatrixXd weights;    // #P by #handles, the weights at the points (rows sum to 1)
  Eigen::Index fromNearestVoxel = 0;  // points with no weighted voxel among their eight corners
};

// P: #P by 3 points (the grid's world space, LPS mm); amounts: #handles. Throws UsageError if amounts
// has the wrong length or a non-finite entry, maxThicknessMm is not finite and >= 0, or the weights are
// empty. Parallel over points (TBB); the result does not depend on the number of threads.
BoneFatThickness boneFatThickness(const BoundedBiharmonicWeights& weights, const MatrixX3d& P,
                                  const Eigen::VectorXd& amounts, const BoneFatOptions& options = {});

}  // namespace vesalius::fat
