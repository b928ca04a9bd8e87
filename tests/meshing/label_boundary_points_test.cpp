// A label's boundary points (meshing/label_boundary_points.h) on painted balls of 2 mm voxels in a rotated
// grid, one well inside and two cut by the grid's top or bottom slice: the points are as many as asked,
// lie on the ball's boundary (within a voxel of its sphere) and within the scan's voxel centres, the cap
// where the scan cuts the ball is counted apart (about the disc the cut leaves), and a seed gives the same
// points. A label filling the grid has voxels but no boundary within the scan; a missing label has none.
#include "vesalius/meshing/label_boundary_points.h"

#include "test_label_maps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace vesalius::meshing {
namespace {

GridGeometry grid() {
  GridGeometry g;
  g.size = {24, 24, 24};
  g.spacing = {2, 2, 2};
  g.origin = {-10, 20, 5};
  g.direction = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  return g;
}

struct Ball {
  Eigen::Vector3d centreIndex;  // continuous index of the centre
  double radiusVoxels;
  double capRadiusVoxels;  // of the disc the grid's edge cuts off (0: not cut)
};

TEST(LabelBoundaryPoints, OnTheBallWithinTheScanWithTheCapApart) {
  const GridGeometry g = grid();
  // Centres 2 voxels inside the top slice and 1.5 inside the bottom one: caps of radius sqrt(8² - 2²) and
  // sqrt(7² - 1.5²) voxels.
  for (const Ball& ball : {Ball{{11.5, 11.5, 11.5}, 8, 0}, Ball{{11.5, 11.5, 21}, 8, std::sqrt(60.0)},
                           Ball{{10, 12, 1.5}, 7, std::sqrt(49 - 2.25)}}) {
    const Eigen::Vector3d centre = g.indexToWorld(ball.centreIndex);
    const double radius = 2 * ball.radiusVoxels;
    const LabelMap map =
        test::paintedLabelMap(g, [&](const Eigen::Vector3d& p) { return (p - centre).norm() <= radius ? 3 : 0; });
    for (int count : {20, 150}) {
      const LabelBoundaryPoints b = labelBoundaryPoints(map, 3, {count, 7});
      ASSERT_TRUE(b.hasVoxels);
      ASSERT_EQ(b.points.rows(), count);
      double worst = 0;
      for (Eigen::Index i = 0; i < b.points.rows(); ++i) {
        const Eigen::Vector3d p = b.points.row(i).transpose(), index = g.worldToIndex(p);
        worst = std::max(worst, std::abs((p - centre).norm() - radius));
        EXPECT_TRUE((index.array() >= -1e-9).all() && (index.array() <= 23 + 1e-9).all()) << index.transpose();
      }
      const double cap = M_PI * std::pow(2 * ball.capRadiusVoxels, 2);
      std::cout << "ball of " << radius << " mm, " << count << " points: farthest " << worst
                << " mm from the sphere; area " << b.area << " mm², cap " << b.scanEdgeArea << " mm² (disc " << cap
                << ")\n";
      EXPECT_LE(worst, 2.0);  // a voxel
      EXPECT_GT(b.area, 0.5 * 4 * M_PI * radius * radius);
      if (cap == 0) {
        EXPECT_NEAR(b.scanEdgeArea, 0.0, 1e-6);
      } else {
        EXPECT_NEAR(b.scanEdgeArea, cap, 0.25 * cap);  // a disc of voxel faces
      }
      ASSERT_EQ(b.stageSeconds.size(), 2u);
      EXPECT_EQ(b.stageSeconds[0].first, "surface");
      EXPECT_EQ(b.stageSeconds[1].first, "spread markers");
      EXPECT_EQ(labelBoundaryPoints(map, 3, {count, 7}).points, b.points);
    }
  }
}

TEST(LabelBoundaryPoints, NoBoundaryWithinTheScanOrNoVoxels) {
  const GridGeometry g = grid();
  const LabelMap full = test::paintedLabelMap(g, [](const Eigen::Vector3d&) { return 2; });
  const LabelBoundaryPoints b = labelBoundaryPoints(full, 2, {10, 1});
  EXPECT_TRUE(b.hasVoxels);
  EXPECT_EQ(b.points.rows(), 0);
  EXPECT_EQ(b.area, 0.0);
  std::cout << "a label filling the grid: cap " << b.scanEdgeArea << " mm²\n";
  EXPECT_NEAR(b.scanEdgeArea, 6 * 48.0 * 48.0, 0.1 * 6 * 48.0 * 48.0);  // the voxels' box, 48 mm a side
  const LabelBoundaryPoints none = labelBoundaryPoints(full, 5, {10, 1});
  EXPECT_FALSE(none.hasVoxels);
  EXPECT_EQ(none.points.rows(), 0);
}

}  // namespace
}  // namespace vesalius::meshing
