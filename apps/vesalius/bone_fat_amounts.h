// Fat from per-bone amounts as `fat edit` and `transfer --fat-amounts` take it: a JSON file
// ({"pelvis": 0.4, ...}) read for fat::boneFatFromAmounts (fat/bone_fat_amounts.h), what it took in the
// report.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/fat/bone_fat_amounts.h"
#include "vesalius/io/report.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::cli {

// Thickness (mm, #V of reference.skin) from the amounts in `amountsPath`; options' sources are set to the
// two paths. Throws as fat::boneFatFromAmounts, and BadInput naming amountsPath for a file that is not a
// JSON object. Warns on stderr of bones with no voxel inside the skin.
Eigen::VectorXd boneFatAtSkin(const ReferenceAnatomy& reference, const std::string& referencePath,
                              const std::string& amountsPath, fat::BoneFatAmountsOptions options, io::Report& report);

}  // namespace vesalius::cli
