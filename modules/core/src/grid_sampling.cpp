// Grid sampling (grid_sampling.h).
#include "vesalius/core/grid_sampling.h"

#include <algorithm>
#include <cmath>

namespace vesalius {

bool insideVoxels(const Eigen::Vector3d& index, const Eigen::Vector3i& size) {
  return (index.array() >= -0.5).all() && (index.array() <= size.cast<double>().array() - 0.5).all();
}

namespace {

template <class T>
double trilinear(const Grid<T>& grid, const Eigen::Vector3d& index) {
  const Eigen::Vector3i& size = grid.geometry.size;
  int low[3], high[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    const double x = std::clamp(index[a], 0.0, double(size[a] - 1));
    low[a] = int(std::floor(x));
    high[a] = std::min(low[a] + 1, size[a] - 1);
    t[a] = x - low[a];
  }
  double value = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double weight = 1.0;
    int at[3];
    for (int a = 0; a < 3; ++a) {
      const bool upper = corner >> a & 1;
      weight *= upper ? t[a] : 1.0 - t[a];
      at[a] = upper ? high[a] : low[a];
    }
    if (weight > 0.0) value += weight * grid.at(at[0], at[1], at[2]);
  }
  return value;
}

}  // namespace

double sampleTrilinear(const Grid<float>& grid, const Eigen::Vector3d& index) { return trilinear(grid, index); }

IndexBox indexBoxAroundBall(const GridGeometry& geometry, const Eigen::Matrix3d& indexPerWorld,
                            const Eigen::Vector3d& p, double radius) {
  const Eigen::Vector3d c = geometry.worldToIndex(p);
  IndexBox box;
  for (int a = 0; a < 3; ++a) {
    const double reach = radius * indexPerWorld.row(a).norm();
    box.lo[a] = std::max(0, int(std::ceil(c[a] - reach)));
    box.hi[a] = std::min(geometry.size[a] - 1, int(std::floor(c[a] + reach)));
  }
  return box;
}

double sampleTrilinear(const Grid<double>& grid, const Eigen::Vector3d& index) { return trilinear(grid, index); }

}  // namespace vesalius
