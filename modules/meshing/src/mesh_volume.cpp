// Inside masks, signed distance fields and covering grids of closed meshes (mesh_volume.h), by OpenVDB.
#include "vesalius/meshing/mesh_volume.h"

#include "pseudonormal_sign.h"
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace vesalius::meshing {
namespace {

// OpenVDB's MeshDataAdapter over our matrices; P holds the vertices already in OpenVDB index space.
struct IndexSpaceMesh {
  const MatrixX3d& P;
  const MatrixX3i& F;
  std::size_t polygonCount() const { return std::size_t(F.rows()); }
  std::size_t pointCount() const { return std::size_t(P.rows()); }
  std::size_t vertexCount(std::size_t) const { return 3; }
  void getIndexSpacePoint(std::size_t n, std::size_t v, openvdb::Vec3d& pos) const {
    const Eigen::Index p = F(Eigen::Index(n), Eigen::Index(v));
    pos = openvdb::Vec3d(P(p, 0), P(p, 1), P(p, 2));
  }
};

void checkClosed(const TriMesh& mesh, const GridGeometry& grid) {
  grid.validate("voxelization grid");
  if (mesh.F.rows() == 0) throw BadInput("", "cannot voxelize a mesh without triangles");
  mesh.validate("");
  const EdgeCounts edges = countEdges(mesh.F);
  if (edges.boundary > 0)
    throw BadInput("", "cannot voxelize an open mesh (" + std::to_string(edges.boundary) +
                           " boundary edges): its inside is undefined");
}

// OpenVDB's signed distance of the mesh at every voxel centre, in index units: the mesh is mapped into
// the grid's continuous index space, where our voxel centres are OpenVDB's integer voxels. Narrow band
// of halfWidth; farther voxels read +halfWidth outside and -halfWidth inside. Index-space distances are
// not mm (spacing and direction distort them), but inside-ness survives the map.
Grid<float> indexSpaceLevelSet(const TriMesh& mesh, const GridGeometry& grid, float halfWidth) {
  openvdb::initialize();  // idempotent and thread-safe
  const Eigen::Matrix3d worldToIndex = (grid.direction * grid.spacing.asDiagonal()).inverse();
  const MatrixX3d P = (mesh.V.rowwise() - grid.origin.transpose()) * worldToIndex.transpose();
  const openvdb::math::Transform::Ptr unit = openvdb::math::Transform::createLinearTransform(1.0);
  const openvdb::FloatGrid::Ptr vdb =
      openvdb::tools::meshToVolume<openvdb::FloatGrid>(IndexSpaceMesh{P, mesh.F}, *unit, halfWidth, halfWidth);
  Grid<float> level(grid, 0.0f);
  const Eigen::Vector3i size = grid.size;
  tbb::parallel_for(tbb::blocked_range<int>(0, size.z()), [&](const tbb::blocked_range<int>& slices) {
    const openvdb::FloatGrid::ConstAccessor accessor = vdb->getConstAccessor();
    for (int k = slices.begin(); k < slices.end(); ++k)
      for (int j = 0; j < size.y(); ++j)
        for (int i = 0; i < size.x(); ++i) level.at(i, j, k) = accessor.getValue(openvdb::Coord(i, j, k));
  });
  return level;
}

// Voxel centres of the linear indices `voxels`, #voxels by 3.
MatrixX3d voxelCentres(const GridGeometry& g, const std::vector<std::size_t>& voxels) {
  const std::size_t nx = std::size_t(g.size.x()), ny = std::size_t(g.size.y());
  MatrixX3d centres(Eigen::Index(voxels.size()), 3);
  for (std::size_t m = 0; m < voxels.size(); ++m) {
    const std::size_t n = voxels[m];
    const Eigen::Vector3d index(double(n % nx), double(n / nx % ny), double(n / (nx * ny)));
    centres.row(Eigen::Index(m)) = g.indexToWorld(index).transpose();
  }
  return centres;
}

// Calls f(m) for each 6-neighbour m (linear index) of voxel n inside a grid of `size`.
template <class F>
void forEachNeighbour(const Eigen::Vector3i& size, std::size_t n, const F& f) {
  const std::int64_t step[3] = {1, size.x(), std::int64_t(size.x()) * size.y()};
  const std::int64_t index[3] = {std::int64_t(n) % step[1], std::int64_t(n) / step[1] % size.y(),
                                 std::int64_t(n) / step[2]};
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-1, 1})
      if (index[axis] + side >= 0 && index[axis] + side < size(axis))
        f(std::size_t(std::int64_t(n) + side * step[axis]));
}

// The voxels near the surface, with exact distances (mm) and signs.
struct NearSurface {
  std::vector<std::size_t> voxels;  // linear indices
  std::vector<double> distance;     // to the closest point on the triangles
};

// Measures voxels outwards from `seeds` (voxels at the surface), layer by layer through the 6-neighbours
// of every voxel closer than `limit` mm, and sets `inside` of each measured voxel by the pseudonormal
// test when `sign` is usable. Every voxel closer than limit - reach is measured, reach being half the sum
// of a voxel's edge lengths (at least half its diagonal): a 6-connected voxel path runs from it to the
// surface within half a diagonal of the straight segment to its closest point, so every voxel on that
// path is closer than limit, and the seeds lie on every piece of surface inside the grid.
NearSurface measureNearSurface(const TriMesh& mesh, const detail::PseudonormalSign& sign, double limit,
                               std::vector<std::size_t> layer, Grid<std::uint8_t>& inside) {
  const GridGeometry& g = inside.geometry;
  const TriangleTree tree(mesh.V, mesh.F);
  std::vector<std::uint8_t> queued(inside.values.size(), 0);
  for (std::size_t n : layer) queued[n] = 1;
  NearSurface near;
  // A layer at a time, so the closest-point queries of a layer run in parallel.
  for (std::vector<std::size_t> next; !layer.empty(); layer.swap(next), next.clear()) {
    const MatrixX3d centres = voxelCentres(g, layer);
    const std::vector<ClosestPoint> closest = tree.closest(centres);
    for (std::size_t m = 0; m < layer.size(); ++m) {
      const double d = std::sqrt(closest[m].squaredDistance);
      near.voxels.push_back(layer[m]);
      near.distance.push_back(d);
      if (sign.usable()) inside.values[layer[m]] = sign.inside(centres.row(Eigen::Index(m)).transpose(), closest[m]);
      if (d >= limit) continue;
      forEachNeighbour(g.size, layer[m], [&](std::size_t n) {
        if (queued[n]) return;
        queued[n] = 1;
        next.push_back(n);
      });
    }
  }
  return near;
}

// Inside (1) or outside (0) at every voxel centre; `near` gets the voxels within nearMm (at least a
// voxel) of the surface with exact distances. OpenVDB's level set, mapped to index space, gives the
// voxels at the surface (|value| < 1 index unit) and a sign everywhere, but its sign near the surface
// comes from a heuristic that errs on a few voxels (143 of 2.7M of the coarse SOFA liver at 0.04 units,
// against the winding number) and its distances away from the surface overestimate. So the near voxels
// are measured exactly and signed by the pseudonormal test, and every other voxel takes the sign of the
// near voxel it is reached from through 6-neighbours: no surface passes between two adjacent voxels
// unless both are within a voxel edge of it, hence near. Voxels reached from no near voxel keep
// OpenVDB's flood-filled sign, as does everything when the mesh is not an oriented manifold.
Grid<std::uint8_t> insideFlags(const TriMesh& mesh, const GridGeometry& grid, double nearMm, NearSurface& near) {
  const Grid<float> level = indexSpaceLevelSet(mesh, grid, 2.0f);
  Grid<std::uint8_t> inside(grid, 0);
  std::vector<std::size_t> seeds;
  for (std::size_t n = 0; n < level.values.size(); ++n) {
    inside.values[n] = level.values[n] < 0.0f;
    if (std::abs(level.values[n]) < 1.0f) seeds.push_back(n);
  }
  const Eigen::RowVector3d edges = (grid.direction * grid.spacing.asDiagonal()).colwise().norm();
  const double reach = 0.5 * edges.sum();
  const detail::PseudonormalSign sign(mesh);
  near = measureNearSurface(mesh, sign, std::max(nearMm, edges.maxCoeff()) + reach, std::move(seeds), inside);
  if (!sign.usable()) return inside;
  std::vector<std::uint8_t> reached(inside.values.size(), 0);
  for (std::size_t n : near.voxels) reached[n] = 1;
  for (std::vector<std::size_t> layer = near.voxels, next; !layer.empty(); layer.swap(next), next.clear())
    for (std::size_t n : layer)
      forEachNeighbour(grid.size, n, [&](std::size_t m) {
        if (reached[m]) return;
        reached[m] = 1;
        inside.values[m] = inside.values[n];
        next.push_back(m);
      });
  return inside;
}

}  // namespace

Grid<std::uint8_t> meshInsideMask(const TriMesh& mesh, const GridGeometry& grid) {
  checkClosed(mesh, grid);
  NearSurface near;
  return insideFlags(mesh, grid, 0.0, near);
}

Grid<float> meshSignedDistance(const TriMesh& mesh, const GridGeometry& grid, const SignedDistanceOptions& options) {
  if (!(options.bandMm > 0.0 && std::isfinite(options.bandMm)))
    throw UsageError("the signed-distance band must be a positive number of mm");
  checkClosed(mesh, grid);
  NearSurface near;
  const Grid<std::uint8_t> inside = insideFlags(mesh, grid, options.bandMm, near);
  const float band = float(options.bandMm);
  Grid<float> distance(grid, band);
  for (std::size_t n = 0; n < inside.values.size(); ++n)
    if (inside.values[n]) distance.values[n] = -band;
  for (std::size_t m = 0; m < near.voxels.size(); ++m)
    distance.values[near.voxels[m]] = std::copysign(std::min(float(near.distance[m]), band),
                                                    distance.values[near.voxels[m]]);
  return distance;
}

GridGeometry coveringGrid(const std::vector<const TriMesh*>& meshes, const CoveringGridOptions& options) {
  if (!(options.voxelSizeMm > 0.0 && std::isfinite(options.voxelSizeMm)) ||
      !(options.marginMm >= 0.0 && std::isfinite(options.marginMm)) || options.maxSize.minCoeff() < 2)
    throw UsageError("a covering grid needs a voxel size > 0 mm, a margin >= 0 mm and a cap of >= 2 voxels");
  Eigen::AlignedBox3d box;
  for (const TriMesh* mesh : meshes) {
    if (!mesh) throw UsageError("coveringGrid was given a null mesh");
    if (!mesh->V.allFinite()) throw BadInput("", "a mesh to cover has a non-finite vertex");
    for (Eigen::Index v = 0; v < mesh->V.rows(); ++v) box.extend(mesh->V.row(v).transpose());
  }
  if (box.isEmpty()) throw BadInput("", "no vertices to cover with a grid");
  const Eigen::Vector3d extent = box.sizes() + Eigen::Vector3d::Constant(2.0 * options.marginMm);
  // n voxel centres span (n - 1) h, so h >= extent / (cap - 1) keeps n within the cap.
  double h = options.voxelSizeMm;
  for (int a = 0; a < 3; ++a) h = std::max(h, extent(a) / (options.maxSize(a) - 1));
  GridGeometry grid;
  grid.spacing = Eigen::Vector3d::Constant(h);
  for (int a = 0; a < 3; ++a)  // the tolerance keeps round-off in extent / h from adding a voxel
    grid.size(a) = std::min(options.maxSize(a), int(std::ceil(extent(a) / h - 1e-9)) + 1);
  grid.origin = box.center() - 0.5 * h * (grid.size.cast<double>() - Eigen::Vector3d::Ones());
  return grid;
}

}  // namespace vesalius::meshing
