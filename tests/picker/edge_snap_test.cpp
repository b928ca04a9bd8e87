// Snapping to the strongest edge: a step edge in a synthetic scan, on an axis-aligned and a rotated grid.
#include "edge_snap.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace vesalius::picker {
namespace {

// A 30^3 scan of 1 mm voxels centred on `centre`: 0 inside the ball of `radius` mm around it, 100 outside.
Image ballScan(const Eigen::Matrix3d& direction, const Eigen::Vector3d& centre, double radius) {
  GridGeometry g;
  g.size = {30, 30, 30};
  g.direction = direction;
  g.origin = centre - direction * Eigen::Vector3d(14.5, 14.5, 14.5);
  Image scan(g);
  for (int k = 0; k < 30; ++k)
    for (int j = 0; j < 30; ++j)
      for (int i = 0; i < 30; ++i)
        scan.at(i, j, k) = (g.indexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm() < radius ? 0.f : 100.f;
  return scan;
}

TEST(EdgeSnap, ClickNearABallSnapsToItsSurface) {
  const Eigen::Vector3d centre(5, -7, 12);
  for (const Eigen::Matrix3d& direction :
       {Eigen::Matrix3d::Identity().eval(),
        Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix()}) {
    const Image scan = ballScan(direction, centre, 8);
    const Eigen::Vector3d click = centre + Eigen::Vector3d(6.5, 1, 0);  // 6.6 mm out: inside, near the edge
    const Eigen::Vector3d snapped = snapToEdge(scan, click, Eigen::Vector3d::UnitZ(), 3);
    EXPECT_NEAR((snapped - centre).norm(), 8, 0.75) << snapped.transpose();  // voxel-sized edge
    EXPECT_NEAR(snapped.z(), click.z(), 1e-9);                               // stays on the slice
  }
}

TEST(EdgeSnap, FlatRegionAndOutsideLeaveTheClick) {
  const Image scan = ballScan(Eigen::Matrix3d::Identity(), {0, 0, 0}, 8);
  const Eigen::Vector3d nearCentre(0.5, 0, 0), outside(100, 0, 0);
  EXPECT_EQ(snapToEdge(scan, nearCentre, Eigen::Vector3d::UnitZ(), 2), nearCentre);
  EXPECT_EQ(snapToEdge(scan, outside, Eigen::Vector3d::UnitZ(), 2), outside);
}

}  // namespace
}  // namespace vesalius::picker
