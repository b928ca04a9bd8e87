// Extract, merge, relabel and crop label maps (label_edit.h).
#include "vesalius/segmentation/label_edit.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace vesalius::segmentation {
namespace {

// A lookup from every possible id to its new id, as a dense table (ids are 16 bits).
using IdTable = std::vector<Label>;

IdTable identityIds() {
  IdTable ids(65536);
  for (std::size_t id = 0; id < ids.size(); ++id) ids[id] = Label(id);
  return ids;
}

LabelMap applyIds(const LabelMap& map, const IdTable& ids) {
  LabelMap out;
  out.labels = Grid<Label>(map.labels.geometry);
  std::transform(map.labels.values.begin(), map.labels.values.end(), out.labels.values.begin(),
                 [&](Label v) { return ids[v]; });
  return out;
}

// The table entries of `map` that survive: each entry with a non-zero new id, under that id.
void carryEntries(const LabelTable& from, const IdTable& ids, LabelTable& to) {
  for (LabelEntry entry : from.entries) {
    if (ids[entry.id] == 0) continue;
    entry.id = ids[entry.id];
    to.add(entry);
  }
}

std::set<Label> presentIds(const Grid<Label>& labels) {
  std::vector<std::uint8_t> seen(65536, 0);
  for (Label v : labels.values) seen[v] = 1;
  std::set<Label> ids;
  for (std::size_t id = 1; id < seen.size(); ++id)
    if (seen[id]) ids.insert(Label(id));
  return ids;
}

}  // namespace

std::vector<Label> resolveLabels(const LabelTable& table, const std::vector<std::string>& idsOrNames) {
  std::vector<Label> ids;
  for (const std::string& idOrName : idsOrNames) ids.push_back(table.resolve(idOrName));
  return ids;
}

LabelMap extractLabels(const LabelMap& map, const std::vector<Label>& ids) {
  IdTable keep(65536, 0);
  for (Label id : ids) keep[id] = id;
  LabelMap out = applyIds(map, keep);
  carryEntries(map.table, keep, out.table);
  return out;
}

LabelMap extractLabels(const LabelMap& map, const std::vector<std::string>& idsOrNames) {
  return extractLabels(map, resolveLabels(map.table, idsOrNames));
}

LabelMap mergeLabels(const LabelMap& map, const std::vector<Label>& ids, const LabelEntry& into) {
  if (into.id == 0) throw UsageError("labels cannot be merged into the background (id 0)");
  IdTable merged = identityIds();
  for (Label id : ids) merged[id] = into.id;
  LabelMap out = applyIds(map, merged);
  IdTable others = identityIds();
  for (Label id : ids) others[id] = 0;
  others[into.id] = 0;
  carryEntries(map.table, others, out.table);
  out.table.add(into);
  return out;
}

LabelMap relabel(const LabelMap& map, const std::map<Label, Label>& idMap) {
  IdTable ids = identityIds();
  for (auto [from, to] : idMap) ids[from] = to;
  // Two labels meeting at one id would be merged silently; ask for mergeLabels instead.
  std::set<Label> sources = presentIds(map.labels);
  for (const LabelEntry& e : map.table.entries) sources.insert(e.id);
  std::map<Label, Label> reached;
  for (Label id : sources) {
    if (ids[id] == 0) continue;
    auto [it, fresh] = reached.emplace(ids[id], id);
    if (!fresh)
      throw UsageError("relabelling would give labels " + std::to_string(it->second) + " and " +
                       std::to_string(id) + " the same id " + std::to_string(ids[id]) + "; merge them instead");
  }
  LabelMap out = applyIds(map, ids);
  carryEntries(map.table, ids, out.table);
  return out;
}

VoxelBox maskBounds(const Mask& mask, double marginMm) {
  if (!(marginMm >= 0.0) || !std::isfinite(marginMm))
    throw UsageError("crop margin must be a finite number of mm >= 0");
  const GridGeometry& g = mask.geometry;
  VoxelBox box{g.size, Eigen::Vector3i::Zero()};
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        if (mask.at(i, j, k)) {
          box.lo = box.lo.cwiseMin(Eigen::Vector3i(i, j, k));
          box.hi = box.hi.cwiseMax(Eigen::Vector3i(i + 1, j + 1, k + 1));
        }
  if ((box.hi.array() <= box.lo.array()).any()) throw BadInput("", "cannot crop to an empty mask");
  for (int a = 0; a < 3; ++a) {
    // A margin that is a whole number of voxels must not round up by a rounding error.
    const int grow = int(std::ceil(marginMm / g.spacing[a] - 1e-9));
    box.lo[a] = std::max(0, box.lo[a] - grow);
    box.hi[a] = std::min(g.size[a], box.hi[a] + grow);
  }
  return box;
}

GridGeometry cropGeometry(const GridGeometry& geometry, const VoxelBox& box) {
  if ((box.lo.array() < 0).any() || (box.hi.array() > geometry.size.array()).any() ||
      (box.hi.array() <= box.lo.array()).any())
    throw UsageError("crop box is empty or leaves the grid");
  GridGeometry out = geometry;
  out.size = box.size();
  out.origin = geometry.indexToWorld(box.lo.cast<double>());
  return out;
}

LabelMap cropLabelMap(const LabelMap& map, const VoxelBox& box) {
  LabelMap out;
  out.labels = cropGrid(map.labels, box);
  const std::set<Label> present = presentIds(out.labels);
  for (const LabelEntry& e : map.table.entries)
    if (present.count(e.id)) out.table.add(e);
  return out;
}

}  // namespace vesalius::segmentation
