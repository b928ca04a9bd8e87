// Cavities of a body sealed at a given opening width (sealed_cavities.h).
#include "vesalius/meshing/sealed_cavities.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

namespace vesalius::meshing {
namespace {

// Index offsets of the voxel centres within `radiusMm` of a voxel centre (mm; direction is orthonormal).
std::vector<Eigen::Vector3i> ballOffsets(const Eigen::Vector3d& spacing, double radiusMm) {
  const Eigen::Vector3i reach = (radiusMm / spacing.array()).floor().cast<int>();
  std::vector<Eigen::Vector3i> offsets;
  for (int k = -reach.z(); k <= reach.z(); ++k)
    for (int j = -reach.y(); j <= reach.y(); ++j)
      for (int i = -reach.x(); i <= reach.x(); ++i)
        if ((Eigen::Vector3d(i, j, k).cwiseProduct(spacing)).norm() <= radiusMm) offsets.emplace_back(i, j, k);
  return offsets;
}

// 1 where the closing of the inside by a ball of radius r holds the voxel. A voxel outside the grid
// counts as far from the surface (not in the dilation).
Grid<std::uint8_t> closing(const Grid<float>& d, double r) {
  const GridGeometry& g = d.geometry;
  const std::vector<Eigen::Vector3i> ball = ballOffsets(g.spacing, r);
  Grid<std::uint8_t> closed(g, 0);
  tbb::parallel_for(tbb::blocked_range<int>(0, g.size.z()), [&](const tbb::blocked_range<int>& ks) {
    for (int k = ks.begin(); k < ks.end(); ++k)
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i) {
          const float here = d.at(i, j, k);
          if (here <= 0) {
            closed.at(i, j, k) = 1;
            continue;
          }
          if (here >= r) continue;
          bool ballInDilation = true;
          for (const Eigen::Vector3i& o : ball) {
            const int a = i + o.x(), b = j + o.y(), c = k + o.z();
            if (!g.contains(a, b, c) || d.at(a, b, c) >= r) {
              ballInDilation = false;
              break;
            }
          }
          closed.at(i, j, k) = ballInDilation;
        }
  });
  return closed;
}

// 1 at the voxels outside `solid` that no 6-connected path outside it joins to the grid's border: a
// depth-first flood of the outside from the border, on linear indices (the outside is most of the grid).
Grid<std::uint8_t> enclosedBackground(const Grid<std::uint8_t>& solid) {
  const GridGeometry& g = solid.geometry;
  const std::int64_t nx = g.size.x(), ny = g.size.y(), nz = g.size.z(), slice = nx * ny;
  Grid<std::uint8_t> enclosed(g, 0);
  for (std::size_t v = 0; v < solid.values.size(); ++v) enclosed.values[v] = !solid.values[v];
  std::vector<std::int64_t> stack;
  const auto reach = [&](std::int64_t v) {
    if (!enclosed.values[std::size_t(v)]) return;
    enclosed.values[std::size_t(v)] = 0;
    stack.push_back(v);
  };
  for (std::int64_t k = 0; k < nz; ++k)
    for (std::int64_t j = 0; j < ny; ++j)
      for (std::int64_t i = 0; i < nx; ++i)
        if (i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1) reach(i + nx * j + slice * k);
  while (!stack.empty()) {
    const std::int64_t v = stack.back();
    stack.pop_back();
    const std::int64_t i = v % nx, j = (v / nx) % ny, k = v / slice;
    if (i > 0) reach(v - 1);
    if (i < nx - 1) reach(v + 1);
    if (j > 0) reach(v - nx);
    if (j < ny - 1) reach(v + nx);
    if (k > 0) reach(v - slice);
    if (k < nz - 1) reach(v + slice);
  }
  return enclosed;
}

}  // namespace

Grid<std::uint8_t> sealedCavities(const Grid<float>& signedDistance, double openingMm) {
  if (!(openingMm > 0) || !std::isfinite(openingMm))
    throw UsageError("sealed cavities: the opening width must be a positive number of mm");
  return enclosedBackground(closing(signedDistance, openingMm / 2));
}

}  // namespace vesalius::meshing
