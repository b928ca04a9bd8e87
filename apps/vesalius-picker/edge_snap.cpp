#include "edge_snap.h"

#include "vesalius/core/grid_sampling.h"

#include <algorithm>
#include <cmath>

namespace vesalius::picker {
namespace {

// The scan at a world point, clamped to the grid's edge voxels.
double valueAt(const Image& scan, const Eigen::Vector3d& world) {
  return sampleTrilinear(scan, scan.geometry.worldToIndex(world));
}

// Central-difference gradient of the scan over `h` mm in world coordinates.
Eigen::Vector3d gradientAt(const Image& scan, const Eigen::Vector3d& world, double h) {
  Eigen::Vector3d gradient;
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d offset = Eigen::Vector3d::Unit(a) * h;
    gradient[a] = (valueAt(scan, world + offset) - valueAt(scan, world - offset)) / (2 * h);
  }
  return gradient;
}

}  // namespace

Eigen::Vector3d snapToEdge(const Image& scan, const Eigen::Vector3d& world, const Eigen::Vector3d& planeNormal,
                           double radius) {
  const GridGeometry& g = scan.geometry;
  const Eigen::Vector3d index = g.worldToIndex(world);
  if (!g.contains(int(std::lround(index.x())), int(std::lround(index.y())), int(std::lround(index.z()))))
    return world;
  const Eigen::Vector3d normal = planeNormal.normalized();
  Eigen::Vector3d direction = gradientAt(scan, world, radius / 2);
  direction -= direction.dot(normal) * normal;
  if (direction.norm() < 1e-9) return world;
  direction.normalize();

  const double h = g.spacing.minCoeff() / 2;  // difference step along the line
  const int samples = int(std::ceil(radius / (h / 2)));
  Eigen::Vector3d strongest = world;
  double strongestChange = 0;
  for (int s = -samples; s <= samples; ++s) {
    const Eigen::Vector3d p = world + direction * (radius * s / samples);
    const double change = std::abs(valueAt(scan, p + h * direction) - valueAt(scan, p - h * direction));
    if (change > strongestChange) {
      strongestChange = change;
      strongest = p;
    }
  }
  return strongest;
}

}  // namespace vesalius::picker
