// Capping a label map's size (Sujar et al. 2018, §3.2): the capped grid covers the same box, a ball keeps its
// centre and volume when resampled, and oblique grids are capped along the axes they point along.
#include "vesalius/segmentation/label_resample.h"

#include "vesalius/core/error.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesalius::segmentation {
namespace {

// A 300 x 60 x 40 map of 1 mm voxels along L, P, S with a ball of radius 15 mm (label 3).
LabelMap ballMap(const Eigen::Matrix3d& direction = Eigen::Matrix3d::Identity()) {
  GridGeometry g;
  g.size = {300, 60, 40};
  g.spacing = {1, 1, 1};
  g.origin = {-20, 5, 100};
  g.direction = direction;
  LabelMap map{Grid<Label>(g, 0), {}};
  map.table.add({3, "ball", {200, 50, 50}});
  const Eigen::Vector3d centre = g.indexToWorld(Eigen::Vector3d(150, 30, 20));
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 60; ++j)
      for (int i = 0; i < 300; ++i)
        if ((g.indexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm() <= 15.0) map.labels.at(i, j, k) = 3;
  return map;
}

Eigen::Vector3d centroid(const LabelMap& map, Label id) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  long n = 0;
  const Eigen::Vector3i& s = map.labels.geometry.size;
  for (int k = 0; k < s.z(); ++k)
    for (int j = 0; j < s.y(); ++j)
      for (int i = 0; i < s.x(); ++i)
        if (map.labels.at(i, j, k) == id) sum += map.labels.geometry.indexToWorld(Eigen::Vector3d(i, j, k)), ++n;
  return sum / double(n);
}

double volumeMm3(const LabelMap& map, Label id) {
  return double(countVoxels(maskOf(map.labels, id))) * map.labels.geometry.spacing.prod();
}

TEST(LabelResample, CapGrowsOnlyTheAxesOverItAndKeepsTheBox) {
  const GridGeometry g = ballMap().labels.geometry;
  const GridGeometry c = cappedGeometry(g, Eigen::Vector3i(250, 120, 700));
  EXPECT_EQ(c.size, Eigen::Vector3i(250, 60, 40));
  EXPECT_NEAR(c.spacing.x(), 1.2, 1e-12);
  EXPECT_EQ(c.spacing.tail<2>(), g.spacing.tail<2>());
  // The outer faces of the first and last voxels along i stay where they were.
  EXPECT_NEAR(c.indexToWorld(Eigen::Vector3d(-0.5, 0, 0)).x(), g.indexToWorld(Eigen::Vector3d(-0.5, 0, 0)).x(), 1e-9);
  EXPECT_NEAR(c.indexToWorld(Eigen::Vector3d(249.5, 0, 0)).x(), g.indexToWorld(Eigen::Vector3d(299.5, 0, 0)).x(),
              1e-9);
  EXPECT_EQ(cappedGeometry(g, Eigen::Vector3i(400, 400, 400)).size, g.size);
  EXPECT_THROW(cappedGeometry(g, Eigen::Vector3i(0, 1, 1)), UsageError);
}

TEST(LabelResample, BallKeepsItsCentreAndVolume) {
  const LabelMap map = ballMap();
  const LabelMap coarse = resampleLabels(map, cappedGeometry(map.labels.geometry, Eigen::Vector3i(100, 120, 700)));
  EXPECT_EQ(coarse.labels.geometry.size, Eigen::Vector3i(100, 60, 40));  // 3 mm along L
  EXPECT_EQ(coarse.table.entries.size(), 1u);
  EXPECT_LT((centroid(coarse, 3) - centroid(map, 3)).norm(), 0.5);
  EXPECT_NEAR(volumeMm3(coarse, 3) / volumeMm3(map, 3), 1.0, 0.03);
}

TEST(LabelResample, ObliqueGridIsCappedAlongTheLpsAxisEachIndexAxisFollows) {
  // Index axis 0 runs (mostly) superior and axis 2 left: the 700 cap now applies to axis 0.
  Eigen::Matrix3d direction;
  direction << 0, 0, 1, 0.1, 1, 0, 1, -0.1, 0;
  direction.col(0).normalize();
  direction.col(1).normalize();
  const LabelMap map = ballMap(direction);
  const GridGeometry c = cappedGeometry(map.labels.geometry, Eigen::Vector3i(20, 120, 700));
  EXPECT_EQ(c.size, Eigen::Vector3i(300, 60, 20));
  EXPECT_TRUE(c.direction.isApprox(direction));
  const LabelMap coarse = resampleLabels(map, c);
  EXPECT_LT((centroid(coarse, 3) - centroid(map, 3)).norm(), 1.0);  // half a 2 mm voxel
  EXPECT_NEAR(volumeMm3(coarse, 3) / volumeMm3(map, 3), 1.0, 0.05);
}

}  // namespace
}  // namespace vesalius::segmentation
