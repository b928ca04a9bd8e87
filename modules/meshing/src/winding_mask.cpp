// Voxels inside a broken surface by the winding number (winding_mask.h).
#include "vesalius/meshing/winding_mask.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vesalius::meshing {
namespace {

// The index-space box [lo, hi] of voxels whose centres may lie in the mesh's bounding box, clipped to
// the grid; empty (lo > hi on some axis) if they miss it.
void indexBox(const TriMesh& mesh, const GridGeometry& g, Eigen::Vector3i& lo, Eigen::Vector3i& hi) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = Eigen::Vector3d::Constant(-INFINITY);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d index = g.worldToIndex(mesh.V.row(v).transpose());
    low = low.cwiseMin(index);
    high = high.cwiseMax(index);
  }
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::max(0, int(std::ceil(low[a])));
    hi[a] = std::min(g.size[a] - 1, int(std::floor(high[a])));
  }
}

}  // namespace

Grid<std::uint8_t> windingNumberMask(const TriMesh& mesh, const GridGeometry& g, const WindingNumberOptions& options) {
  if (mesh.F.rows() == 0) throw BadInput("", "the surface to voxelize has no triangles");
  mesh.validate("");
  g.validate("");
  Grid<std::uint8_t> mask(g, 0);
  Eigen::Vector3i lo, hi;
  indexBox(mesh, g, lo, hi);
  if ((hi.array() < lo.array()).any()) return mask;
  const Eigen::Vector3i n = hi - lo + Eigen::Vector3i::Ones();
  std::vector<std::int64_t> voxel;
  voxel.reserve(std::size_t(n.prod()));
  MatrixX3d centres(n.prod(), 3);
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) {
        centres.row(Eigen::Index(voxel.size())) = g.indexToWorld(Eigen::Vector3d(i, j, k)).transpose();
        voxel.push_back(g.linearIndex(i, j, k));
      }
  const Eigen::VectorXd w = windingNumbers(mesh.V, mesh.F, centres, options);
  const double sign = enclosedVolume(mesh.V, mesh.F) < 0 ? -1.0 : 1.0;
  for (std::size_t p = 0; p < voxel.size(); ++p) mask.values[std::size_t(voxel[p])] = sign * w[Eigen::Index(p)] >= 0.5;
  return mask;
}

}  // namespace vesalius::meshing
