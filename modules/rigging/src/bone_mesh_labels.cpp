// The labelled image of a body's skin and bone meshes (bone_mesh_labels.h).
#include "vesalius/rigging/bone_mesh_labels.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/winding_mask.h"

namespace vesalius::rigging {

segmentation::Mask skinInsideMask(const TriMesh& skin, const GridGeometry& grid, const std::string& source) {
  try {
    return segmentation::largestComponent(
        segmentation::openMm(meshing::meshInsideMask(skin, grid), grid.spacing.maxCoeff()),
        segmentation::Connectivity::Face);
  } catch (const BadInput& e) {
    if (!e.file().empty()) throw;
    throw BadInput(source, "skin: " + e.problem());
  }
}

LabelMap boneMeshLabelMap(const TriMesh& skin, const std::vector<BoneMeshes>& bones, const GridGeometry& grid,
                          const std::string& source) {
  const segmentation::Mask body = skinInsideMask(skin, grid, source);
  const Label bodyLabel = Label(bones.size() + 1);
  LabelMap map;
  map.labels = Grid<Label>(grid, 0);
  for (std::size_t v = 0; v < body.values.size(); ++v) map.labels.values[v] = body.values[v] ? bodyLabel : 0;
  map.table.add({bodyLabel, "body", defaultLabelColor(bodyLabel)});
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const Label id = Label(b + 1);
    map.table.add({id, bones[b].name, defaultLabelColor(id)});
    for (const TriMesh* mesh : bones[b].meshes) {
      segmentation::Mask inside;
      try {
        inside = meshing::windingNumberMask(*mesh, grid);
      } catch (const BadInput& e) {
        throw BadInput(source, "bone '" + bones[b].name + "': " + e.problem());
      }
      for (std::size_t v = 0; v < inside.values.size(); ++v)
        if (inside.values[v] && body.values[v]) map.labels.values[v] = id;
    }
  }
  return map;
}

}  // namespace vesalius::rigging
