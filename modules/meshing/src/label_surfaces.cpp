// Surfaces of several labels (label_surface.h).
#include "vesalius/meshing/label_surface.h"

#include <set>
#include <string>

namespace vesalius::meshing {
namespace {

std::vector<Label> labelsToMesh(const LabelMap& labels, const std::vector<Label>& ids) {
  if (!ids.empty()) return ids;
  std::vector<Label> all;
  for (const LabelEntry& entry : labels.table.entries) all.push_back(entry.id);
  if (!all.empty()) return all;
  const std::set<Label> present(labels.labels.values.begin(), labels.labels.values.end());
  for (Label id : present)
    if (id != 0) all.push_back(id);
  return all;
}

}  // namespace

std::vector<LabelSurface> labelSurfaces(const LabelMap& labels, const std::vector<Label>& ids,
                                        const SurfaceOptions& options, Progress* progress) {
  std::vector<bool> present(std::size_t(1) << 16, false);
  for (Label v : labels.labels.values) present[v] = true;
  std::vector<LabelSurface> surfaces;
  for (Label id : labelsToMesh(labels, ids)) {
    if (!present[id]) continue;
    const LabelEntry* entry = labels.table.find(id);
    LabelSurface surface{id, entry ? entry->name : std::to_string(id), {}};
    if (progress) progress->begin("surface " + surface.name);
    surface.mesh = labelSurface(labels, id, options);
    if (progress) progress->end();
    surfaces.push_back(std::move(surface));
  }
  return surfaces;
}

}  // namespace vesalius::meshing
