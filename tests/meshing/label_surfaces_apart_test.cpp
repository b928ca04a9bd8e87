// Label surfaces of one label map moved apart where they cross (meshing::moveLabelSurfacesApart): a block
// of 4 mm cubes with a smaller block set into its top, which the grid's last slice cuts, each surfaced on
// its own by labelSurface at a coarse face count (smoothed, decimated, its volume given back), so the small
// block's rounded, re-inflated sides cross the big block's smoothed notch. Measured apart from the method
// (deepest_inside.h). The promise: afterwards no vertex the scan sees lies inside the other surface deeper
// than Dicko et al.'s 1 mm tolerance and none at all once the rounds converge, and the caps beyond the
// scan's last voxel centres stay; without a field of view, the same for every vertex.
#include "deepest_inside.h"
#include "test_label_maps.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/label_surfaces_apart.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <utility>

namespace vesalius::meshing {
namespace {

using test::deepestEitherWay;
using test::paintedLabelMap;

GridGeometry blocksGrid() {
  GridGeometry grid;
  grid.size = Eigen::Vector3i(20, 20, 12);
  grid.spacing = Eigen::Vector3d::Constant(4.0);
  return grid;
}

// The big block (label 1) and the small one set into it (label 2), each labelSurface'd on its own.
std::pair<TriMesh, TriMesh> blocks() {
  const LabelMap map = paintedLabelMap(blocksGrid(), [](const Eigen::Vector3d& p) {
    const bool inBig = (p.array() >= 8).all() && p.x() <= 68 && p.y() <= 68;
    const bool inSmall = inBig && (p.head<2>().array() >= 24).all() && (p.head<2>().array() <= 48).all() && p.z() >= 24;
    return inSmall ? 2 : inBig ? 1 : 0;
  });
  SurfaceOptions options;
  options.targetFaces = 400;
  return {labelSurface(map, 1, options), labelSurface(map, 2, options)};
}

TEST(LabelSurfacesApart, TwoLabelsThatShareFacesEndApartAndTheScansCapsStay) {
  const GridGeometry grid = blocksGrid();
  auto [big, small] = blocks();
  const TriMesh bigBefore = big, smallBefore = small;
  const double before = deepestEitherWay(big, small);
  const LabelSurfacesApart apart = moveLabelSurfacesApart({&big, &small}, &grid);
  const double after = deepestEitherWay(big, small);
  std::printf("two labels sharing faces: deepest %.2f mm before, %.2f after (the method's %.2f, %.2f); %ld vertices "
              "inside before, %ld after, %d rounds, largest move %.2f mm\n",
              before, after, apart.deepestBeforeMm, apart.deepestAfterMm, apart.insideBefore, apart.insideAfter,
              apart.rounds, apart.largestMoveMm);
  EXPECT_GT(before, 0.1);
  EXPECT_GT(apart.insideBefore, 0);
  EXPECT_EQ(apart.insideAfter, 0);
  EXPECT_LE(after, 1.0);
  // Each vertex moves by at most half of the deepest crossing and half the margin per round.
  EXPECT_LE(apart.largestMoveMm, apart.rounds * (before + 0.1) / 2 + 1e-9);
  // The caps where the grid's last slice (z = 44 mm) cuts both labels stay where labelSurface put them.
  for (const auto& [moved, original] : {std::pair{&big, &bigBefore}, std::pair{&small, &smallBefore}})
    for (Eigen::Index v = 0; v < moved->V.rows(); ++v) {
      if (!grid.seesPoint(original->V.row(v).transpose())) {
        EXPECT_EQ(moved->V.row(v), original->V.row(v));
      }
    }
}

// Without a field of view (bones brought onto labels, which go on beyond the scan) every vertex counts:
// blocks that a scan elsewhere does not see are left as they are, and without one they end apart.
TEST(LabelSurfacesApart, WithoutAFieldOfViewEveryVertexEndsApart) {
  auto [big, small] = blocks();
  const double before = deepestEitherWay(big, small);
  GridGeometry elsewhere = blocksGrid();
  elsewhere.origin = Eigen::Vector3d(500, 0, 0);
  const TriMesh bigBefore = big;
  const LabelSurfacesApart unseen = moveLabelSurfacesApart({&big, &small}, &elsewhere);
  EXPECT_EQ(unseen.insideBefore, 0);
  EXPECT_EQ(big.V, bigBefore.V);
  const LabelSurfacesApart apart = moveLabelSurfacesApart({&big, &small}, nullptr);
  const double after = deepestEitherWay(big, small);
  std::printf("every vertex: deepest %.2f mm before, %.2f after; %ld vertices inside before, %ld after, %d rounds\n",
              before, after, apart.insideBefore, apart.insideAfter, apart.rounds);
  EXPECT_GT(apart.insideBefore, 0);
  EXPECT_EQ(apart.insideAfter, 0);
  EXPECT_LE(after, 1.0);
}

// The big block held fixed (a scan's own tissue): it keeps every vertex, and the small one moves all the way
// out of it.
TEST(LabelSurfacesApart, AFixedSurfaceStaysAndTheOtherMovesOut) {
  const GridGeometry grid = blocksGrid();
  auto [big, small] = blocks();
  const TriMesh bigBefore = big;
  const double before = deepestEitherWay(big, small);
  LabelSurfacesApartOptions o;
  o.fixed = {true, false};
  const LabelSurfacesApart apart = moveLabelSurfacesApart({&big, &small}, &grid, o);
  const double after = deepestEitherWay(big, small);
  std::printf("the big block fixed: deepest %.2f mm before, %.2f after; %ld vertices inside before, %ld after, "
              "%d rounds, largest move %.2f mm\n",
              before, after, apart.insideBefore, apart.insideAfter, apart.rounds, apart.largestMoveMm);
  EXPECT_EQ(big.V, bigBefore.V);
  EXPECT_GT(apart.insideBefore, 0);
  EXPECT_EQ(apart.insideAfter, 0);
  EXPECT_LE(after, 1.0);
  o.fixed = {true};
  EXPECT_THROW(moveLabelSurfacesApart({&big, &small}, &grid, o), UsageError);
}

TEST(LabelSurfacesApart, NullSurfacesAndBadOptionsAreRefused) {
  GridGeometry grid;
  grid.size = Eigen::Vector3i::Constant(4);
  EXPECT_THROW(moveLabelSurfacesApart({nullptr}, &grid), UsageError);
  TriMesh empty;
  LabelSurfacesApartOptions o;
  o.rounds = -1;
  EXPECT_THROW(moveLabelSurfacesApart({&empty}, &grid, o), UsageError);
}

}  // namespace
}  // namespace vesalius::meshing
