// The fat editor of Dicko et al. 2013, §6 on a reference anatomy: per-bone fat amounts spread over the bounded
// biharmonic weights of the reference's bones (bounded_biharmonic_weights.h) on a voxel grid inside its
// skin, combined at the skin's vertices (bone_fat_thickness.h):
//
//   thickness(x) = maxThicknessMm · Σ_j w_j(x) · amount_j
//
// The editor's bones are the reference's bone groups, the bones that move by one map in §8 (both hips
// and the sacrum are "pelvis"); a bone without a group is one of its own. Deviations: Dicko et al. 2013 precomputes
// the weights once per reference; here they are computed for each call, on a grid of voxelSizeMm (10 mm
// takes minutes on the full body, 20 mm seconds). A bone's voxels are its inside (if its mesh is closed)
// and the voxels whose centre lies within half a voxel diagonal of its surface, so that no bone is too thin
// to have one; a voxel claimed by two bones keeps the first in the reference's order. A bone with no voxel
// inside the skin has no weight (listed in BoneFatAmounts::withoutVoxels).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::fat {

struct BoneFatAmountsOptions {
  double voxelSizeMm = 15;     // of the weights' grid
  double maxThicknessMm = 50;  // the thickness an amount of 1 gives (Dicko et al. 2013 gives amounts no unit)
  double defaultAmount = 0;    // of the bones `amounts` does not name
  std::string referenceSource;  // names the reference in BadInput messages
  std::string amountsSource;    // names the amounts in BadInput messages
};

// One bone (group) with weights, in the order of the weights' handles.
struct BoneFatBone {
  std::string name;
  double amount = 0;
  std::int64_t voxels = 0;  // its handle voxels
  int iterations = 0;       // of its weight's solve (bounded_biharmonic_weights.h)
  std::int64_t atZero = 0, atOne = 0;
  double kktResidual = 0;
  bool projectedNewton = false;
};

struct BoneFatAmounts {
  Eigen::VectorXd thickness;  // #V of reference.skin, mm
  GridGeometry grid;          // of the weights
  std::vector<BoneFatBone> bones;          // the bones with weights
  std::vector<std::string> withoutVoxels;  // bones with no voxel inside the skin: their amounts have no effect
  std::int64_t voxels = 0, freeVoxels = 0, unreachableVoxels = 0;  // of the weights' domain
  double maxSumDeviation = 0;              // of the weights from a partition of unity
  Eigen::Index verticesFromNearestVoxel = 0;
  double seconds = 0;  // voxelizing, weights and combination
};

// The editor's bones (group names, else bone names) in the reference's order.
std::vector<std::string> boneFatBoneNames(const ReferenceAnatomy& reference);

// Throws what boneFatFromAmounts throws before it looks at the amounts: UsageError for a voxel size
// <= 0, a maximum thickness or default amount < 0 or not finite, or a default amount over 1000 mm of fat;
// BadInput naming options.referenceSource if the reference has no bones.
void checkBoneFatOptions(const ReferenceAnatomy& reference, const BoneFatAmountsOptions& options);

// amounts: (bone or group name, amount) pairs; bones not named get options.defaultAmount. Throws as
// checkBoneFatOptions, then BadInput naming options.amountsSource for a name that is no bone group (or one
// bone of a group), an amount that is NaN or < 0, or over 1000 mm of fat; BadInput naming
// options.referenceSource if no bone lies inside the skin.
BoneFatAmounts boneFatFromAmounts(const ReferenceAnatomy& reference,
                                  const std::vector<std::pair<std::string, double>>& amounts,
                                  const BoneFatAmountsOptions& options = {});

}  // namespace vesalius::fat
