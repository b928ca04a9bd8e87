// A label's boundary points (label_boundary_points.h).
#include "vesalius/meshing/label_boundary_points.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"

namespace vesalius::meshing {

LabelBoundaryPoints labelBoundaryPoints(const LabelMap& map, Label id, const LabelBoundaryPointsOptions& options,
                                        Progress* progress) {
  LabelBoundaryPoints result;
  result.points.resize(0, 3);
  StageClock clock(result.stageSeconds);
  const std::vector<LabelSurface> surfaces = labelSurfaces(map, {id}, {}, progress);
  clock.end("surface");
  if (surfaces.empty()) return result;
  result.hasVoxels = true;
  const TriMesh& surface = surfaces.front().mesh;
  const TriMesh boundary = withinScan(surface, map.labels.geometry);
  result.area = triangleAreas(boundary.V, boundary.F).sum();
  result.scanEdgeArea = triangleAreas(surface.V, surface.F).sum() - result.area;
  if (boundary.F.rows() == 0) return result;
  result.points = spreadSurfacePoints(boundary, options.count, options.seed);
  clock.end("spread markers");
  return result;
}

}  // namespace vesalius::meshing
