// Label-map operations on small masks whose answers are known by construction.
#include "vesalius/segmentation/label_ops.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

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

// A ball with a finger tip of 2 x 2 x 2 voxels touching it: across a face, an edge or only a corner.
// Full connectivity keeps the tip in each case; face connectivity only where a face joins it.
TEST(LabelOps, LargestComponentByFaceOrFullConnectivity) {
  const GridGeometry g = cube(24);
  const Mask body = ball(g, {10, 10, 10}, 6);
  // The ball's last voxel along +x is (16, 10, 10); each tip starts one step from it.
  const struct {
    const char* joint;
    Eigen::Vector3i corner;
    bool faceKeeps;
  } tips[] = {{"a face", {17, 10, 10}, true}, {"an edge", {17, 11, 10}, false}, {"a corner", {17, 11, 11}, false}};
  for (const auto& tip : tips) {
    Mask both = body;
    for (int d = 0; d < 8; ++d)
      both.at(tip.corner.x() + d % 2, tip.corner.y() + d / 2 % 2, tip.corner.z() + d / 4) = 1;
    ASSERT_EQ(countVoxels(both), countVoxels(body) + 8) << tip.joint;
    const std::int64_t full = countVoxels(largestComponent(both, Connectivity::Full));
    const std::int64_t face = countVoxels(largestComponent(both, Connectivity::Face));
    std::cout << "tip joined at " << tip.joint << ": full keeps " << full << ", face " << face << " of "
              << countVoxels(both) << " voxels\n";
    EXPECT_EQ(full, countVoxels(both)) << tip.joint;
    EXPECT_EQ(face, countVoxels(body) + (tip.faceKeeps ? 8 : 0)) << tip.joint;
  }
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

TEST(LabelOps, SliceWiseFillRespectsTheAxisAndTheHoleArea) {
  // Two square rings in every slice k: around a 2x2 hole and around an 8x8 hole (1 mm pixels). The
  // stack of rings is open at k = 0 and k = last, so only a slice-wise fill closes them.
  GridGeometry g = cube(20);
  Mask rings(g, 0);
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) {
        const bool small = i >= 1 && i <= 4 && j >= 1 && j <= 4 && !(i >= 2 && i <= 3 && j >= 2 && j <= 3);
        const bool big = i >= 7 && i <= 16 && j >= 7 && j <= 16 && !(i >= 8 && i <= 15 && j >= 8 && j <= 15);
        rings.at(i, j, k) = small || big;
      }
  EXPECT_EQ(countVoxels(fillHoles3d(rings)), countVoxels(rings));
  EXPECT_EQ(countVoxels(fillHolesSliceWise(rings, 2)), countVoxels(rings) + 20 * (4 + 64));
  EXPECT_EQ(countVoxels(fillHolesSliceWise(rings, 2, 10.0)), countVoxels(rings) + 20 * 4);
  EXPECT_EQ(countVoxels(fillHolesSliceWise(rings, 0)), countVoxels(rings));
  EXPECT_THROW(fillHolesSliceWise(rings, 3), UsageError);
}

TEST(LabelOps, ComponentsTouchingKeepsOnlySeededComponents) {
  const GridGeometry g = cube(20);
  const Mask a = ball(g, {5, 5, 5}, 3), b = ball(g, {14, 14, 14}, 3);
  Mask seeds(g, 0);
  seeds.at(14, 14, 14) = 1;
  EXPECT_EQ(countVoxels(componentsTouching(maskOr(a, b), seeds)), countVoxels(b));
}

TEST(LabelOps, BodyHolesAreFilledAlsoWhereTheLastSliceCutsThem) {
  // A body filling the field of view along z, with an enclosed pocket and a tube of air along z
  // open at the first and last slices (as bowel gas cut by the scan's ends): both are body.
  const GridGeometry g = cube(20);
  Mask body(g, 0);
  for (int k = 0; k < 20; ++k)
    for (int j = 2; j < 18; ++j)
      for (int i = 2; i < 18; ++i) {
        const bool pocket = i >= 5 && i < 8 && j >= 5 && j < 8 && k >= 8 && k < 11;
        const bool tube = i >= 12 && i < 14 && j >= 12 && j < 14;
        body.at(i, j, k) = !pocket && !tube;
      }
  const Mask solid = fillBodyHoles(body);
  EXPECT_EQ(countVoxels(solid), 16 * 16 * 20);
  EXPECT_EQ(countVoxels(fillHoles3d(body)), countVoxels(body) + 27);  // 3-D alone misses the tube
}

TEST(LabelOps, AxialAxisFollowsTheDirection) {
  GridGeometry g = cube(4);
  EXPECT_EQ(axialAxis(g), 2);
  g.direction << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // j runs inferior: a coronal acquisition
  EXPECT_EQ(axialAxis(g), 1);
}

TEST(LabelOps, MorphologyRejectsBadRadii) {
  const Mask m(cube(4), 1);
  EXPECT_THROW(dilateMm(m, -1.0), UsageError);
  EXPECT_THROW(erodeMm(m, std::nan("")), UsageError);
  // Nothing outside the grid counts as background: a full grid survives erosion.
  EXPECT_EQ(countVoxels(erodeMm(m, 2.0)), countVoxels(m));
}

}  // namespace
}  // namespace vesalius::segmentation
