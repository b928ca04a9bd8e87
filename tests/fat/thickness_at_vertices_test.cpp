// Fat thickness carried to skin mesh vertices: a sphere mesh on a spherical shell, a skin two voxels
// thick (the reason for taking the maximum), and vertices past the masks filled from their neighbours.
#include "vesalius/core/error.h"
#include "vesalius/fat/thickness_at_vertices.h"

#include "test_shapes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

namespace vesalius::fat {
namespace {

struct Shell {
  Mask skin, fat;
  Eigen::Vector3d centre;  // world
};

// Skin R-1.5 < r <= R and fat of `width` beneath it around `centreIndex`, on a grid of spacing s.
Shell shell(int n, double s, double R, double width, int cutAboveK = 1 << 30) {
  GridGeometry g;
  g.size = Eigen::Vector3i(n, n, n);
  g.spacing = Eigen::Vector3d(s, s, s);
  g.origin = Eigen::Vector3d(5, -3, 2);
  Shell out{Mask(g, 0), Mask(g, 0), g.indexToWorld(Eigen::Vector3d::Constant((n - 1) / 2.0))};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double r = (g.indexToWorld(Eigen::Vector3d(i, j, k)) - out.centre).norm();
        if (k > cutAboveK) continue;  // the field of view ends here
        out.skin.at(i, j, k) = r <= R && r > R - 1.5 * s;
        out.fat.at(i, j, k) = r <= R - 1.5 * s && r > R - 1.5 * s - width;
      }
  return out;
}

TEST(ThicknessAtVertices, SphereMeshOnASphericalShellReadsTheShellWidth) {
  const double s = 1.2, R = 30, width = 9;
  const Shell sh = shell(57, s, R, width);
  const FatForest forest(sh.skin, sh.fat);
  // The mesh on the outer face of the skin, as a surface of the skin label would lie.
  const TriMesh mesh = test::sphere(4, R, sh.centre);
  const VertexThickness t = thicknessAtVertices(forest, mesh.V, mesh.F);
  EXPECT_EQ(t.measured, mesh.V.rows());
  EXPECT_EQ(t.filled, 0);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    // Skin centre to deepest fat centre: width within a voxel diagonal, plus the 26-neighbour overestimate.
    EXPECT_GE(t.thickness[v], width - std::sqrt(3.0) * s) << v;
    EXPECT_LE(t.thickness[v], 1.1281 * (width + std::sqrt(3.0) * s)) << v;
  }
  EXPECT_NEAR(t.thickness.mean(), width, 0.08 * width);
}

TEST(ThicknessAtVertices, TwoVoxelSkinTakesTheInnerVoxelsThickness) {
  GridGeometry g;
  g.size = Eigen::Vector3i(12, 12, 14);
  g.spacing = Eigen::Vector3d(1.0, 1.0, 0.8);
  Mask skin(g, 0), fat(g, 0);
  for (int k = 0; k < 14; ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) {
        skin.at(i, j, k) = k >= 12;          // outer skin k = 13, inner skin k = 12
        fat.at(i, j, k) = k >= 4 && k < 12;  // 8 layers: 6.4 mm
      }
  // The paper's per-tree thickness alone (no gathering): the outer skin's trees are just themselves.
  FatForestOptions paper;
  paper.gatherRadiusMm = 0;
  const FatForest forest(skin, fat, paper);
  EXPECT_EQ(forest.thickness().at(6, 6, 13), 0.0f);
  EXPECT_NEAR(forest.thickness().at(6, 6, 12), 6.4, 1e-5);
  // Gathering over one voxel diagonal gives the outer skin its column's value.
  EXPECT_NEAR(FatForest(skin, fat).thickness().at(6, 6, 13), 6.4, 1e-5);
  // A flat mesh half a voxel above the outer skin centres (the skin's outer face).
  TriMesh plane;
  plane.V.resize(4, 3);
  plane.V << 3, 3, 13.4 * 0.8, 8, 3, 13.4 * 0.8, 8, 8, 13.4 * 0.8, 3, 8, 13.4 * 0.8;
  plane.F.resize(2, 3);
  plane.F << 0, 1, 2, 0, 2, 3;
  const VertexThickness t = thicknessAtVertices(forest, plane.V, plane.F);
  for (int v = 0; v < 4; ++v) EXPECT_NEAR(t.thickness[v], 6.4, 1e-5);
}

TEST(ThicknessAtVertices, VerticesPastTheMasksAreFilledFromNeighboursAndCounted) {
  const double s = 1.5, R = 27, width = 8;
  // The masks end at k = 36 of 49 (centre k = 24): the sphere's cap 9 mm high above has no skin.
  const Shell sh = shell(49, s, R, width, 36);
  const FatForest forest(sh.skin, sh.fat);
  const TriMesh mesh = test::sphere(4, R, sh.centre);
  const VertexThickness t = thicknessAtVertices(forest, mesh.V, mesh.F);
  EXPECT_GT(t.filled, 50);
  EXPECT_EQ(t.measured + t.filled, mesh.V.rows());
  EXPECT_EQ(t.unreached, 0);
  double lo = 1e9, hi = -1e9;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    ASSERT_TRUE(std::isfinite(t.thickness[v]));
    if (t.source[v] == VertexThickness::kMeasured)
      lo = std::min(lo, t.thickness[v]), hi = std::max(hi, t.thickness[v]);
    else
      EXPECT_GT(mesh.V(v, 2), sh.centre.z() + 12 * s - 2 * s) << v;  // only the cap is filled
  }
  // Filled values are means of measured ones, so they stay in the measured range.
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    EXPECT_GE(t.thickness[v], lo - 1e-9);
    EXPECT_LE(t.thickness[v], hi + 1e-9);
  }
  // A mesh component far from any skin is reached by nothing: 0, counted.
  const TriMesh far = concatenate(mesh, test::sphere(1, 5, sh.centre + Eigen::Vector3d(500, 0, 0)));
  const VertexThickness u = thicknessAtVertices(forest, far.V, far.F);
  EXPECT_EQ(u.unreached, 18);  // an octahedron split once: 18 vertices
  EXPECT_EQ(u.thickness.tail(18).cwiseAbs().maxCoeff(), 0.0);
}

TEST(ThicknessAtVertices, ResultsDoNotDependOnTheNumberOfThreads) {
  const Shell sh = shell(49, 1.5, 27, 8, 36);
  const TriMesh mesh = test::sphere(4, 27, sh.centre);
  const FatForest many(sh.skin, sh.fat);
  const VertexThickness a = thicknessAtVertices(many, mesh.V, mesh.F);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const FatForest single(sh.skin, sh.fat);
  const VertexThickness b = thicknessAtVertices(single, mesh.V, mesh.F);
  EXPECT_EQ(many.thickness().values, single.thickness().values);
  EXPECT_EQ(many.root(), single.root());
  EXPECT_EQ(a.thickness, b.thickness);
  EXPECT_EQ(a.source, b.source);
}

TEST(ThicknessAtVertices, NegativeRadiusIsAUsageError) {
  const Shell sh = shell(20, 1, 8, 3);
  const FatForest forest(sh.skin, sh.fat);
  VertexThicknessOptions options;
  options.radiusMm = -1;
  const TriMesh mesh = test::sphere(1, 8, sh.centre);
  EXPECT_THROW(thicknessAtVertices(forest, mesh.V, mesh.F, options), UsageError);
}

}  // namespace
}  // namespace vesalius::fat
