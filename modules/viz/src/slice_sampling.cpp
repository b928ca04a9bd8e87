// Sampling a scan and its labels on a slice plane (slice_planes.h).
#include "slice_planes.h"

#include "vesalius/core/grid_sampling.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace vesalius::viz::detail {

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
      if (!insideVoxels(index, g.size)) continue;
      const std::size_t p = std::size_t(y) * plane.width + x;
      out.inside[p] = 1;
      out.scan[p] = float(sampleTrilinear(scan, index));
      const Eigen::Vector3i nearest =
          index.array().round().cast<int>().max(0).min(g.size.array() - 1).matrix();
      out.labels[p] = labels.at(nearest.x(), nearest.y(), nearest.z());
    }
  return out;
}

}  // namespace vesalius::viz::detail
