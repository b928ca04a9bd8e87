// Surfaces of several labels (label_surface.h): one scan of the map finds every label's box, then the
// labels are surfaced in parallel (TBB), one task each. The VTK filters of a label are its own objects,
// so tasks share nothing but the read-only label map; results keep the requested order.
#include "vesalius/meshing/label_surface.h"

#include "label_surface_in_box.h"

#include <tbb/parallel_for.h>
#include <vtkObjectFactory.h>

#include <atomic>
#include <string>

namespace vesalius::meshing {
namespace {

// The ids to surface that have voxels, in order: `ids`, else the table's, else every non-zero label present.
std::vector<Label> labelsToMesh(const LabelMap& labels, const std::vector<Label>& ids,
                                const std::vector<LabelBox>& boxes) {
  auto present = [&](Label id) { return id < boxes.size() && boxes[id].voxels > 0; };
  std::vector<Label> wanted = ids;
  if (wanted.empty())
    for (const LabelEntry& entry : labels.table.entries) wanted.push_back(entry.id);
  if (wanted.empty())
    for (std::size_t id = 1; id < boxes.size(); ++id) wanted.push_back(Label(id));
  std::vector<Label> result;
  for (Label id : wanted)
    if (present(id)) result.push_back(id);
  return result;
}

}  // namespace

std::vector<LabelSurface> labelSurfaces(const LabelMap& labels, const std::vector<Label>& ids,
                                        const SurfaceOptions& options, Progress* progress) {
  const std::vector<LabelBox> boxes = labelBoxes(labels.labels);
  std::vector<LabelSurface> surfaces;
  for (Label id : labelsToMesh(labels, ids, boxes)) {
    const LabelEntry* entry = labels.table.find(id);
    surfaces.push_back({id, entry ? entry->name : std::to_string(id), {}});
  }
  // VTK fills its object-factory registry on first use without a lock: fill it here, before the threads.
  vtkObjectFactory::GetRegisteredFactories();
  if (progress) progress->begin("surfaces", std::to_string(surfaces.size()) + " labels");
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(std::size_t(0), surfaces.size(), [&](std::size_t s) {
    LabelSurface& surface = surfaces[s];
    surface.mesh = detail::labelSurfaceInBox(labels, surface.id, boxes[surface.id], options);
    if (progress) progress->update(double(++done) / double(surfaces.size()));
  });
  if (progress) progress->end();
  return surfaces;
}

}  // namespace vesalius::meshing
