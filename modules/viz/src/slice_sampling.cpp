// Sampling a scan and its labels on a slice plane (slice_planes.h).
#include "slice_planes.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace vesalius::viz::detail {
namespace {

bool insideGrid(const Eigen::Vector3d& index, const Eigen::Vector3i& size) {
  for (int a = 0; a < 3; ++a)
    if (!(index[a] >= -0.5 && index[a] <= size[a] - 0.5)) return false;
  return true;
}

// Trilinear interpolation at a continuous index, neighbours clamped to the grid (the half voxel at the
// border takes the border value).
float trilinear(const Image& scan, const Eigen::Vector3d& index) {
  const Eigen::Vector3i& size = scan.geometry.size;
  int lo[3], hi[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    const double f = std::floor(index[a]);
    t[a] = index[a] - f;
    lo[a] = std::clamp(int(f), 0, size[a] - 1);
    hi[a] = std::clamp(int(f) + 1, 0, size[a] - 1);
  }
  double sum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    double weight = 1.0;
    int at[3];
    for (int a = 0; a < 3; ++a) {
      const bool upper = corner >> a & 1;
      weight *= upper ? t[a] : 1.0 - t[a];
      at[a] = upper ? hi[a] : lo[a];
    }
    if (weight > 0.0) sum += weight * scan.at(at[0], at[1], at[2]);
  }
  return float(sum);
}

}  // namespace

PlaneSamples samplePlane(const Image& scan, const Grid<Label>& labels, const SlicePlane& plane) {
  const GridGeometry& g = scan.geometry;
  const Eigen::Matrix3d worldToIndex = (g.direction * g.spacing.asDiagonal()).inverse();
  const Eigen::Vector3d start = worldToIndex * (plane.corner - g.origin);
  const Eigen::Vector3d stepX = worldToIndex * plane.right, stepY = worldToIndex * plane.down;
  const std::size_t count = std::size_t(plane.width) * plane.height;
  PlaneSamples out{std::vector<float>(count, 0.0f), std::vector<Label>(count, 0),
                   std::vector<std::uint8_t>(count, 0)};
  for (int y = 0; y < plane.height; ++y)
    for (int x = 0; x < plane.width; ++x) {
      const Eigen::Vector3d index = start + x * stepX + y * stepY;
      if (!insideGrid(index, g.size)) continue;
      const std::size_t p = std::size_t(y) * plane.width + x;
      out.inside[p] = 1;
      out.scan[p] = trilinear(scan, index);
      const Eigen::Vector3i nearest =
          index.array().round().cast<int>().max(0).min(g.size.array() - 1).matrix();
      out.labels[p] = labels.at(nearest.x(), nearest.y(), nearest.z());
    }
  return out;
}

}  // namespace vesalius::viz::detail
