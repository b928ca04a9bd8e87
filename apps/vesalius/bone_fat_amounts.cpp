#include "bone_fat_amounts.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fat/bone_fat_thickness.h"
#include "vesalius/fat/bounded_biharmonic_weights.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/text_file.h"
#include "vesalius/meshing/mesh_volume.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace vesalius::cli {

namespace {

// The fat editor's bones (§6): a reference's bone groups, the bones that move by one map in §8 (both
// hips and the sacrum are "pelvis"); a bone without a group is one of its own.
struct BoneHandles {
  std::vector<std::string> names;  // #handles
  std::vector<int> ofTissue;       // per tissue: its handle, -1 if it is not a bone
};

BoneHandles boneHandles(const ReferenceAnatomy& reference) {
  BoneHandles h;
  for (const ReferenceTissue& t : reference.tissues) {
    h.ofTissue.push_back(-1);
    if (t.kind != TissueKind::Bone) continue;
    const std::string name = t.group.empty() ? t.name : t.group;
    const auto it = std::find(h.names.begin(), h.names.end(), name);
    h.ofTissue.back() = int(it - h.names.begin());
    if (it == h.names.end()) h.names.push_back(name);
  }
  return h;
}

// {"bone or group": amount, ...}; bones not named get `defaultAmount`.
Eigen::VectorXd readAmounts(const std::string& path, const BoneHandles& h, const ReferenceAnatomy& reference,
                            double defaultAmount) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(io::readTextFile(path));
  } catch (const nlohmann::json::exception& e) {
    throw BadInput(path, std::string("not valid JSON: ") + e.what());
  }
  if (!json.is_object()) throw BadInput(path, "expected an object of bone names and fat amounts, e.g. {\"pelvis\": 0.4}");
  Eigen::VectorXd amounts = Eigen::VectorXd::Constant(Eigen::Index(h.names.size()), defaultAmount);
  for (const auto& [key, value] : json.items()) {
    const auto it = std::find(h.names.begin(), h.names.end(), key);
    if (it == h.names.end()) {
      for (std::size_t t = 0; t < reference.tissues.size(); ++t)
        if (reference.tissues[t].name == key && h.ofTissue[t] >= 0)
          throw BadInput(path, "'" + key + "' is one bone of the group '" + h.names[h.ofTissue[t]] + "'; give the group's amount");
      std::string known;
      for (const std::string& n : h.names) known += (known.empty() ? "" : ", ") + n;
      throw BadInput(path, "no bone or bone group '" + key + "' in the reference (its bones: " + known + ")");
    }
    if (!value.is_number() || !std::isfinite(value.get<double>()) || value.get<double>() < 0)
      throw BadInput(path, "the amount of '" + key + "' must be a number >= 0");
    amounts[it - h.names.begin()] = value.get<double>();
  }
  return amounts;
}

// Voxels of the skin's inside: −1 outside, handle + 1 on a bone (its inside, if the mesh is closed, and
// the voxels whose centre lies within half a voxel diagonal of its surface, so that no bone is too thin
// to have one), 0 elsewhere. A voxel claimed by two bones keeps the first in the reference's order.
Grid<std::int32_t> boneLabels(const ReferenceAnatomy& reference, const BoneHandles& h, double voxelSize) {
  meshing::CoveringGridOptions options;
  options.voxelSizeMm = voxelSize;
  options.marginMm = voxelSize;
  const GridGeometry g = meshing::coveringGrid({&reference.skin}, options);
  const Grid<std::uint8_t> inside = meshing::meshInsideMask(reference.skin, g);
  Grid<std::int32_t> labels(g, -1);
  for (std::size_t v = 0; v < labels.values.size(); ++v) labels.values[v] = inside.values[v] ? 0 : -1;
  const double reach = 0.5 * g.spacing.norm();
  for (std::size_t t = 0; t < reference.tissues.size(); ++t) {
    if (h.ofTissue[t] < 0) continue;
    const TriMesh& bone = reference.tissues[t].mesh;
    const std::int32_t label = h.ofTissue[t] + 1;
    if (io::summarize(bone).boundaryEdges == 0) {
      const Grid<std::uint8_t> in = meshing::meshInsideMask(bone, g);
      for (std::size_t v = 0; v < labels.values.size(); ++v)
        if (in.values[v] && labels.values[v] == 0) labels.values[v] = label;
    }
    const TriangleTree tree(bone.V, bone.F);
    const Eigen::Vector3d lo = g.worldToIndex(bone.V.colwise().minCoeff().transpose()),
                          hi = g.worldToIndex(bone.V.colwise().maxCoeff().transpose());
    const Eigen::Vector3i from = lo.cwiseMin(hi).array().floor().cast<int>().matrix() - Eigen::Vector3i::Ones(),
                          to = lo.cwiseMax(hi).array().ceil().cast<int>().matrix() + Eigen::Vector3i::Ones();
    for (int k = std::max(0, from.z()); k <= std::min(to.z(), g.size.z() - 1); ++k)
      for (int j = std::max(0, from.y()); j <= std::min(to.y(), g.size.y() - 1); ++j)
        for (int i = std::max(0, from.x()); i <= std::min(to.x(), g.size.x() - 1); ++i)
          if (labels.at(i, j, k) == 0 &&
              tree.closest(g.indexToWorld(Eigen::Vector3d(i, j, k))).squaredDistance <= reach * reach)
            labels.at(i, j, k) = label;
  }
  return labels;
}

}  // namespace

Eigen::VectorXd boneFatAtSkin(const ReferenceAnatomy& reference, const std::string& referencePath,
                              const std::string& amountsPath, const BoneFatSettings& settings, io::Report& report) {
  const double voxelSizeMm = settings.voxelSizeMm, maxThicknessMm = settings.maxThicknessMm,
               defaultAmount = settings.defaultAmount;
  if (!(voxelSizeMm > 0) || !(maxThicknessMm >= 0) || !std::isfinite(maxThicknessMm) || !(defaultAmount >= 0))
    throw UsageError("fat amounts: the voxel size must be > 0, the maximum thickness and default amount >= 0");
  const BoneHandles h = boneHandles(reference);
  if (h.names.empty()) throw BadInput(referencePath, "the reference has no bones for the fat editor");
  // No body holds a metre of fat; beyond that an amount is a typing error (or, as 1e308, an infinity).
  constexpr double kMostThicknessMm = 1000;
  if (maxThicknessMm * defaultAmount > kMostThicknessMm)
    throw UsageError("fat amounts: --default-amount times --max-thickness is at most " +
                     std::to_string(int(kMostThicknessMm)) + " mm of fat");
  const Eigen::VectorXd amounts = readAmounts(amountsPath, h, reference, defaultAmount);
  for (Eigen::Index b = 0; b < amounts.size(); ++b)
    if (amounts[b] * maxThicknessMm > kMostThicknessMm) {
      std::ostringstream text;
      text << "the amount of '" << h.names[std::size_t(b)] << "' is " << amounts[b] << ": times --max-thickness "
           << maxThicknessMm << " mm that is more than " << kMostThicknessMm << " mm of fat";
      throw BadInput(amountsPath, text.str());
    }
  const auto start = std::chrono::steady_clock::now();
  Grid<std::int32_t> labels = boneLabels(reference, h, voxelSizeMm);
  // Handles with no voxel (a bone outside the skin) have no weight; the others are numbered anew.
  std::vector<std::int64_t> count(h.names.size(), 0);
  for (const std::int32_t l : labels.values) if (l > 0) ++count[l - 1];
  std::vector<std::int32_t> renumbered(h.names.size(), 0);
  std::vector<int> kept;
  for (std::size_t j = 0; j < h.names.size(); ++j)
    if (count[j] > 0) kept.push_back(int(j)), renumbered[j] = std::int32_t(kept.size());
  if (kept.empty()) throw BadInput(referencePath, "no bone lies inside the skin");
  for (std::int32_t& l : labels.values) if (l > 0) l = renumbered[l - 1];
  const fat::BoundedBiharmonicWeights w = fat::boundedBiharmonicWeights(labels, int(kept.size()));
  Eigen::VectorXd keptAmounts(Eigen::Index(kept.size()));
  nlohmann::json bones = nlohmann::json::array();
  for (std::size_t k = 0; k < kept.size(); ++k) {
    keptAmounts[Eigen::Index(k)] = amounts[kept[k]];
    bones.push_back({{"name", h.names[kept[k]]}, {"amount", amounts[kept[k]]}, {"voxels", count[kept[k]]},
                     {"iterations", w.iterations[k]}, {"at_zero", w.atZero[k]}, {"at_one", w.atOne[k]},
                     {"kkt_residual", w.kktResidual[k]}, {"projected_newton", bool(w.projectedNewton[k])}});
  }
  fat::BoneFatOptions options;
  options.maxThicknessMm = maxThicknessMm;
  const fat::BoneFatThickness t = fat::boneFatThickness(w, reference.skin.V, keptAmounts, options);
  report.stage("bone weights", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  report.parameter("fat_amounts", amountsPath);
  report.parameter("fat_voxel_size_mm", labels.geometry.spacing.x());
  report.parameter("fat_max_thickness_mm", maxThicknessMm);
  report.parameter("fat_default_amount", defaultAmount);
  report.metric("bone_weights", {{"grid", {labels.geometry.size.x(), labels.geometry.size.y(), labels.geometry.size.z()}},
                                 {"voxels", w.voxel.size()}, {"free_voxels", w.freeVoxels},
                                 {"unreachable_voxels", w.unreachable}, {"max_sum_deviation", w.maxSumDeviation},
                                 {"vertices_from_nearest_voxel", t.fromNearestVoxel}, {"bones", bones}});
  for (std::size_t j = 0; j < h.names.size(); ++j)
    if (!count[j])
      std::cerr << "vesalius: warning: bone '" << h.names[j] << "' has no voxel inside the skin at "
                << labels.geometry.spacing.x() << " mm; its amount has no effect\n";
  return t.thickness;
}


}  // namespace vesalius::cli
