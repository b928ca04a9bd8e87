#include "vesalius/fat/bone_fat_amounts.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fat/bone_fat_thickness.h"
#include "vesalius/fat/bounded_biharmonic_weights.h"
#include "vesalius/meshing/mesh_volume.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace vesalius::fat {

namespace {

// No body holds a metre of fat; beyond that an amount is a typing error (or, as 1e308, an infinity).
constexpr double kMostThicknessMm = 1000;

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

Eigen::VectorXd amountsOfHandles(const std::vector<std::pair<std::string, double>>& given, const BoneHandles& h,
                                 const ReferenceAnatomy& reference, const BoneFatAmountsOptions& o) {
  Eigen::VectorXd amounts = Eigen::VectorXd::Constant(Eigen::Index(h.names.size()), o.defaultAmount);
  for (const auto& [key, value] : given) {
    const auto it = std::find(h.names.begin(), h.names.end(), key);
    if (it == h.names.end()) {
      for (std::size_t t = 0; t < reference.tissues.size(); ++t)
        if (reference.tissues[t].name == key && h.ofTissue[t] >= 0)
          throw BadInput(o.amountsSource,
                         "'" + key + "' is one bone of the group '" + h.names[h.ofTissue[t]] + "'; give the group's amount");
      std::string known;
      for (const std::string& n : h.names) known += (known.empty() ? "" : ", ") + n;
      throw BadInput(o.amountsSource, "no bone or bone group '" + key + "' in the reference (its bones: " + known + ")");
    }
    if (!std::isfinite(value) || value < 0)
      throw BadInput(o.amountsSource, "the amount of '" + key + "' must be a number >= 0");
    amounts[it - h.names.begin()] = value;
  }
  for (Eigen::Index b = 0; b < amounts.size(); ++b)
    if (amounts[b] * o.maxThicknessMm > kMostThicknessMm) {
      std::ostringstream text;
      text << "the amount of '" << h.names[std::size_t(b)] << "' is " << amounts[b] << ": times --max-thickness "
           << o.maxThicknessMm << " mm that is more than " << kMostThicknessMm << " mm of fat";
      throw BadInput(o.amountsSource, text.str());
    }
  return amounts;
}

// Voxels of the skin's inside: −1 outside, handle + 1 on a bone, 0 elsewhere (the header's rules).
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
    if (countEdges(bone.F).boundary == 0) {
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

std::vector<std::string> boneFatBoneNames(const ReferenceAnatomy& reference) { return boneHandles(reference).names; }

void checkBoneFatOptions(const ReferenceAnatomy& reference, const BoneFatAmountsOptions& o) {
  if (!(o.voxelSizeMm > 0) || !(o.maxThicknessMm >= 0) || !std::isfinite(o.maxThicknessMm) || !(o.defaultAmount >= 0))
    throw UsageError("fat amounts: the voxel size must be > 0, the maximum thickness and default amount >= 0");
  if (boneHandles(reference).names.empty())
    throw BadInput(o.referenceSource, "the reference has no bones for the fat editor");
  if (o.maxThicknessMm * o.defaultAmount > kMostThicknessMm)
    throw UsageError("fat amounts: --default-amount times --max-thickness is at most " +
                     std::to_string(int(kMostThicknessMm)) + " mm of fat");
}

BoneFatAmounts boneFatFromAmounts(const ReferenceAnatomy& reference,
                                  const std::vector<std::pair<std::string, double>>& given,
                                  const BoneFatAmountsOptions& o) {
  checkBoneFatOptions(reference, o);
  const BoneHandles h = boneHandles(reference);
  const Eigen::VectorXd amounts = amountsOfHandles(given, h, reference, o);
  const auto start = std::chrono::steady_clock::now();
  Grid<std::int32_t> labels = boneLabels(reference, h, o.voxelSizeMm);
  // Handles with no voxel (a bone outside the skin) have no weight; the others are numbered anew.
  std::vector<std::int64_t> count(h.names.size(), 0);
  for (const std::int32_t l : labels.values)
    if (l > 0) ++count[l - 1];
  std::vector<std::int32_t> renumbered(h.names.size(), 0);
  std::vector<int> kept;
  for (std::size_t j = 0; j < h.names.size(); ++j)
    if (count[j] > 0) kept.push_back(int(j)), renumbered[j] = std::int32_t(kept.size());
  if (kept.empty()) throw BadInput(o.referenceSource, "no bone lies inside the skin");
  for (std::int32_t& l : labels.values)
    if (l > 0) l = renumbered[l - 1];
  const BoundedBiharmonicWeights w = boundedBiharmonicWeights(labels, int(kept.size()));
  BoneFatAmounts out;
  Eigen::VectorXd keptAmounts(Eigen::Index(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) {
    keptAmounts[Eigen::Index(k)] = amounts[kept[k]];
    out.bones.push_back({h.names[kept[k]], amounts[kept[k]], count[kept[k]], w.iterations[k], w.atZero[k], w.atOne[k],
                         w.kktResidual[k], bool(w.projectedNewton[k])});
  }
  BoneFatOptions options;
  options.maxThicknessMm = o.maxThicknessMm;
  const BoneFatThickness t = boneFatThickness(w, reference.skin.V, keptAmounts, options);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.thickness = t.thickness;
  out.grid = labels.geometry;
  out.voxels = std::int64_t(w.voxel.size());
  out.freeVoxels = w.freeVoxels;
  out.unreachableVoxels = w.unreachable;
  out.maxSumDeviation = w.maxSumDeviation;
  out.verticesFromNearestVoxel = t.fromNearestVoxel;
  for (std::size_t j = 0; j < h.names.size(); ++j)
    if (!count[j]) out.withoutVoxels.push_back(h.names[j]);
  return out;
}

}  // namespace vesalius::fat
