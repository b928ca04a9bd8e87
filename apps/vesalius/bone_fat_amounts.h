// The fat editor of seed 000 §6 as `fat edit` and `transfer --fat-amounts` take it: per-bone fat amounts
// from a JSON file ({"pelvis": 0.4, ...}; bones the file does not name get defaultAmount) spread over the
// bounded biharmonic weights of the reference's bone groups (fat/bounded_biharmonic_weights.h) on a voxel
// grid inside its skin.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/io/report.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::cli {

struct BoneFatSettings {
  double voxelSizeMm = 15;     // of the weights' grid: 10 mm takes minutes on the full body, 20 mm seconds
  double maxThicknessMm = 50;  // the thickness an amount of 1 gives (the seed gives amounts no unit)
  double defaultAmount = 0;    // of the bones the file does not name
};

// Thickness (mm, #V of reference.skin) = maxThicknessMm · Σ_j w_j · amount_j at the skin's vertices; what it
// took goes into `report`. Throws BadInput naming amountsPath (unknown bone, bad JSON, negative amount) or
// referencePath (no bones inside the skin), UsageError for bad numbers.
Eigen::VectorXd boneFatAtSkin(const ReferenceAnatomy& reference, const std::string& referencePath,
                              const std::string& amountsPath, const BoneFatSettings& settings, io::Report& report);

}  // namespace vesalius::cli
