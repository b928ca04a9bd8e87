#include "bone_fat_amounts.h"

#include "vesalius/io/fat_amounts_io.h"

#include <nlohmann/json.hpp>

#include <iostream>

namespace vesalius::cli {

Eigen::VectorXd boneFatAtSkin(const ReferenceAnatomy& reference, const std::string& referencePath,
                              const std::string& amountsPath, fat::BoneFatAmountsOptions options, io::Report& report) {
  options.referenceSource = referencePath;
  options.amountsSource = amountsPath;
  fat::checkBoneFatOptions(reference, options);  // before the file, so that bad options fail first
  const fat::BoneFatAmounts f = fat::boneFatFromAmounts(reference, io::readFatAmounts(amountsPath), options);
  nlohmann::json bones = nlohmann::json::array();
  for (const fat::BoneFatBone& b : f.bones)
    bones.push_back({{"name", b.name}, {"amount", b.amount}, {"voxels", b.voxels}, {"iterations", b.iterations},
                     {"at_zero", b.atZero}, {"at_one", b.atOne}, {"kkt_residual", b.kktResidual},
                     {"projected_newton", b.projectedNewton}});
  report.stage("bone weights", f.seconds);
  report.parameter("fat_amounts", amountsPath);
  report.parameter("fat_voxel_size_mm", f.grid.spacing.x());
  report.parameter("fat_max_thickness_mm", options.maxThicknessMm);
  report.parameter("fat_default_amount", options.defaultAmount);
  report.metric("bone_weights", {{"grid", {f.grid.size.x(), f.grid.size.y(), f.grid.size.z()}},
                                 {"voxels", f.voxels}, {"free_voxels", f.freeVoxels},
                                 {"unreachable_voxels", f.unreachableVoxels}, {"max_sum_deviation", f.maxSumDeviation},
                                 {"vertices_from_nearest_voxel", f.verticesFromNearestVoxel}, {"bones", bones}});
  for (const std::string& name : f.withoutVoxels)
    std::cerr << "vesalius: warning: bone '" << name << "' has no voxel inside the skin at " << f.grid.spacing.x()
              << " mm; its amount has no effect\n";
  return f.thickness;
}

}  // namespace vesalius::cli
