// Closed surfaces from broken ones by the winding number (closed_surface.h).
#include "vesalius/meshing/closed_surface.h"

#include "well_composed.h"
#include "vesalius/core/error.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/small_pieces.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/winding_mask.h"

#include <algorithm>
#include <cstdint>
#include <string>

namespace vesalius::meshing {
namespace {

void checkInput(const TriMesh& mesh, const ClosedSurfaceOptions& options) {
  if (options.resolution < 8 || options.targetFaces < 0)
    throw UsageError("closing a surface needs a resolution of at least 8 voxels and target faces >= 0");
  if (mesh.F.rows() == 0) throw BadInput("", "the surface has no triangles to close");
  mesh.validate("");
}

// The grid: `resolution` voxels along the longest side, two voxels of margin so the outer layer is
// outside, and the cap just large enough for that.
GridGeometry windingGrid(const TriMesh& mesh, int resolution) {
  const double longest = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).maxCoeff();
  if (!(longest > 0)) throw BadInput("", "the surface to close has no extent");
  CoveringGridOptions grid;
  grid.voxelSizeMm = longest / resolution;
  grid.marginMm = 2.0 * grid.voxelSizeMm;
  grid.maxSize = Eigen::Vector3i::Constant(resolution + 6);
  return coveringGrid({&mesh}, grid);
}

// Pieces of the solid smaller than a 2x2x2 block are below the grid's resolution: single voxels where the
// approximate winding number of a fin (two back-to-back triangles, exactly 0 beside them) strays above 1/2.
constexpr std::int64_t kLeastPieceVoxels = 8;

// Label 1 where the winding number is >= 1/2 (winding_mask.h), but for pieces under kLeastPieceVoxels; the
// grid's outer layer, two voxels beyond the mesh's bounding box, stays 0 as makeWellComposed requires.
Grid<Label> insideVoxels(const TriMesh& mesh, const GridGeometry& g, const WindingNumberOptions& options) {
  Grid<std::uint8_t> mask = windingNumberMask(mesh, g, options);
  dropSmallPieces(mask, kLeastPieceVoxels);
  Grid<Label> inside(g, 0);
  std::copy(mask.values.begin(), mask.values.end(), inside.values.begin());
  return inside;
}

}  // namespace

TriMesh closedSurface(const TriMesh& mesh, const ClosedSurfaceOptions& options) {
  checkInput(mesh, options);
  LabelMap solid;
  solid.labels = insideVoxels(mesh, windingGrid(mesh, options.resolution), options.winding);
  if (std::find(solid.labels.values.begin(), solid.labels.values.end(), Label(1)) == solid.labels.values.end())
    throw BadInput("", "the surface encloses no voxel at resolution " + std::to_string(options.resolution));
  // Voxels meeting across an edge or a corner only would give the iso-surface non-manifold edges.
  detail::makeWellComposed(solid.labels);
  SurfaceOptions surface;
  surface.smoothingIterations = options.smoothingIterations;
  surface.targetFaces = options.targetFaces;
  TriMesh closed = labelSurface(solid, 1, surface);
  closed.faceAttributes = {};
  return closed;
}

}  // namespace vesalius::meshing
