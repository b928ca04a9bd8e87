// Label-map operations on small masks whose answers are known by construction.
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

namespace vesalius::segmentation {
namespace {

GridGeometry cube(int n, double spacing = 1.0) {
  GridGeometry g;
  g.size = Eigen::Vector3i(n, n, n);
  g.spacing = Eigen::Vector3d::Constant(spacing);
  return g;
}

Mask ball(const GridGeometry& g, const Eigen::Vector3d& centre, double radius) {
  Mask m(g, 0);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        m.at(i, j, k) = (g.indexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm() <= radius;
  return m;
}

TEST(LabelOps, DiceOfKnownOverlaps) {
  const GridGeometry g = cube(10);
  Mask a(g, 0), b(g, 0);
  for (int i = 0; i < 4; ++i) a.at(i, 0, 0) = 1;
  for (int i = 2; i < 6; ++i) b.at(i, 0, 0) = 1;
  EXPECT_DOUBLE_EQ(diceCoefficient(a, b), 2.0 * 2 / 8);
  EXPECT_DOUBLE_EQ(diceCoefficient(a, a), 1.0);
  EXPECT_DOUBLE_EQ(diceCoefficient(Mask(g, 0), Mask(g, 0)), 1.0);
}

TEST(LabelOps, LargestComponentAndSmallComponents) {
  const GridGeometry g = cube(20);
  const Mask big = ball(g, {5, 5, 5}, 4), small = ball(g, {15, 15, 15}, 1.5);
  const Mask both = maskOr(big, small);
  EXPECT_EQ(countVoxels(largestComponent(both)), countVoxels(big));
  EXPECT_EQ(countVoxels(removeSmallComponents(both, countVoxels(small) + 1)), countVoxels(big));
}

TEST(LabelOps, FillHolesFillsACavityButNotTheOutside) {
  const GridGeometry g = cube(20);
  const Mask shell = maskAndNot(ball(g, {10, 10, 10}, 7), ball(g, {10, 10, 10}, 4));
  EXPECT_EQ(countVoxels(fillHoles3d(shell)), countVoxels(ball(g, {10, 10, 10}, 7)));
}

TEST(LabelOps, DistanceAndMorphologyAreInMillimetres) {
  // 0.5 mm voxels: a 2 mm erosion of a 6 mm ball leaves a 4 mm ball, to within a voxel.
  const GridGeometry g = cube(40, 0.5);
  const Eigen::Vector3d c(10, 10, 10);
  const Mask eroded = erodeMm(ball(g, c, 6.0), 2.0);
  EXPECT_EQ(countVoxels(maskAndNot(eroded, ball(g, c, 4.5))), 0);
  EXPECT_EQ(countVoxels(maskAndNot(ball(g, c, 3.5), eroded)), 0);
  const Mask dilated = dilateMm(ball(g, c, 3.0), 2.0);
  EXPECT_EQ(countVoxels(maskAndNot(dilated, ball(g, c, 5.5))), 0);
  EXPECT_EQ(countVoxels(maskAndNot(ball(g, c, 4.5), dilated)), 0);
  const Grid<float> d = distanceToMaskMm(ball(g, c, 3.0));
  EXPECT_NEAR(d.at(39, 20, 20), 19.5 - 10.0 - 3.0, 0.5);  // voxel 39 is at 19.5 mm
}

}  // namespace
}  // namespace vesalius::segmentation
