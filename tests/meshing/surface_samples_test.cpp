// Evenly spread surface points (meshing/surface_samples.h) on surfaces whose area is known: they lie on
// the surface, no two are much closer than the ideal spacing sqrt(area / count), no part of the surface
// is far from one, two spheres get points in proportion to their areas, a seed always gives the same
// points, and a label cut by the scan's edge gets none on the cap that closes it.
#include "vesalius/meshing/surface_samples.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/meshing/label_surface.h"

#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace vesalius::meshing {
namespace {

double area(const TriMesh& m) {
  double a = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d p = m.V.row(m.F(f, 0)), q = m.V.row(m.F(f, 1)), r = m.V.row(m.F(f, 2));
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

double minSpacing(const MatrixX3d& P) {
  double d = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (Eigen::Index j = i + 1; j < P.rows(); ++j) d = std::min(d, (P.row(i) - P.row(j)).norm());
  return d;
}

// The farthest any of `probes` is from its nearest point of P.
double coveringRadius(const MatrixX3d& P, const MatrixX3d& probes) {
  double worst = 0;
  for (Eigen::Index i = 0; i < probes.rows(); ++i)
    worst = std::max(worst, (P.rowwise() - probes.row(i)).rowwise().norm().minCoeff());
  return worst;
}

const double kRadius = 10.0;
const TriMesh& sphere() {
  static const TriMesh s = test::sphere(5, kRadius, Eigen::Vector3d(3, -4, 5));  // 8192 triangles
  return s;
}

TEST(SpreadSurfacePoints, LieOnTheSurface) {
  const MatrixX3d P = spreadSurfacePoints(sphere(), 200, 1);
  ASSERT_EQ(P.rows(), 200);
  const TriangleTree tree(sphere().V, sphere().F);
  double worst = 0;
  for (const ClosestPoint& c : tree.closest(P)) worst = std::max(worst, std::sqrt(c.squaredDistance));
  RecordProperty("max_distance_to_mesh", std::to_string(worst));
  EXPECT_LT(worst, 1e-9);
}

// Farthest-point sampling keeps every pair of chosen points at least the covering radius r of the
// candidates apart (each point was the farthest candidate when it was chosen). N discs of radius r cover
// the area A only if N (3 sqrt(3) / 2) r^2 >= A (the hexagonal covering is the thinnest), so on a surface
// flat at that scale the smallest spacing is at least 0.62 sqrt(A / N), whatever the seed; a hexagonal
// packing would reach 1.07 sqrt(A / N). Measured on the sphere (area 1256 mm^2, 200 points: sqrt(A / N) =
// 2.51 mm), seeds 1..20, default 32 candidates a point: the smallest spacing is 0.745-0.782 sqrt(A / N)
// (0.70-0.73 with 8 candidates a point, 0.77-0.80 with 128; 0.05 for 200 random points). We assert 0.7,
// above the 0.62 guarantee and below every measurement. The covering radius against 4000 probe points
// (how far a surface point is from its nearest marker) is measured at most 0.885 sqrt(A / N); we assert 1.
TEST(SpreadSurfacePoints, EvenlySpread) {
  const int n = 200;
  const double ideal = std::sqrt(area(sphere()) / n);
  const MatrixX3d probes = spreadSurfacePoints(sphere(), 4000, 99, {8000});  // dense, even probe points
  double worstSpacing = 1e9, worstCover = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const MatrixX3d P = spreadSurfacePoints(sphere(), n, seed);
    worstSpacing = std::min(worstSpacing, minSpacing(P) / ideal);
    worstCover = std::max(worstCover, coveringRadius(P, probes) / ideal);
  }
  RecordProperty("min_spacing_ratio", std::to_string(worstSpacing));
  RecordProperty("covering_radius_ratio", std::to_string(worstCover));
  EXPECT_GE(worstSpacing, 0.7);
  EXPECT_LE(worstCover, 1.0);

  // Without the selection (as many candidates as points) the points are merely random and clump.
  const double random = minSpacing(spreadSurfacePoints(sphere(), n, 1, {n})) / ideal;
  RecordProperty("random_min_spacing_ratio", std::to_string(random));
  EXPECT_LT(random, 0.4);
}

// Even spreading is by area: spheres of radius 10 and 5 (areas 4 : 1) get 4/5 and 1/5 of the points.
TEST(SpreadSurfacePoints, PointsFollowTheArea) {
  const TriMesh two = concatenate(sphere(), test::sphere(5, 5.0, Eigen::Vector3d(40, 0, 0)));
  const MatrixX3d P = spreadSurfacePoints(two, 250, 7);
  const long onSmall = (P.col(0).array() > 30).count();
  RecordProperty("points_on_small_sphere", std::to_string(onSmall));
  EXPECT_NEAR(double(onSmall), 50.0, 4.0);
}

TEST(SpreadSurfacePoints, SameSeedSamePoints) {
  const MatrixX3d a = spreadSurfacePoints(sphere(), 50, 42), b = spreadSurfacePoints(sphere(), 50, 42);
  EXPECT_EQ(a, b);
  const MatrixX3d c = spreadSurfacePoints(sphere(), 50, 43);
  EXPECT_GT((a - c).rowwise().norm().maxCoeff(), 1.0);
}

// The random numbers are fixed by the standard (mt19937_64 and our own conversion to doubles), so these
// values hold with any compiler and standard library: the first point is the first candidate.
TEST(SpreadSurfacePoints, SeedGivesTheSamePointsEverywhere) {
  TriMesh triangle;
  triangle.V.resize(3, 3);
  triangle.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  triangle.F.resize(1, 3);
  triangle.F << 0, 1, 2;
  std::mt19937_64 rng(5);
  rng();  // the draw that picks the triangle
  const double r = std::sqrt(double(rng() >> 11) * 0x1.0p-53), v = double(rng() >> 11) * 0x1.0p-53;
  const MatrixX3d P = spreadSurfacePoints(triangle, 3, 5);
  EXPECT_DOUBLE_EQ(P(0, 0), r * (1 - v));
  EXPECT_DOUBLE_EQ(P(0, 1), r * v);
  EXPECT_EQ(P(0, 2), 0.0);
  // The same numbers written out, so that a change of generator is caught.
  EXPECT_NEAR(P(0, 0), 0.15199872235036885, 1e-15);
  EXPECT_NEAR(P(0, 1), 0.044201712938850161, 1e-15);
}

TEST(SpreadSurfacePoints, BadCountsAreUsageErrors) {
  EXPECT_THROW(spreadSurfacePoints(sphere(), 0, 1), UsageError);
  EXPECT_THROW(spreadSurfacePoints(sphere(), -5, 1), UsageError);
  EXPECT_THROW(spreadSurfacePoints(sphere(), 101, 1, {100}), UsageError);
  EXPECT_EQ(spreadSurfacePoints(sphere(), 100, 1, {100}).rows(), 100);
  try {
    spreadSurfacePoints(sphere(), 101, 1, {100});
  } catch (const UsageError& e) {
    EXPECT_STREQ(e.what(), "cannot choose 101 points from 100 candidates");
  }
}

TEST(SpreadSurfacePoints, SurfaceWithoutAreaIsBadInput) {
  EXPECT_THROW(spreadSurfacePoints(TriMesh{}, 10, 1), BadInput);
  TriMesh flat = sphere();
  flat.V.setZero();
  EXPECT_THROW(spreadSurfacePoints(flat, 10, 1), BadInput);
  TriMesh broken = sphere();
  broken.V(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(spreadSurfacePoints(broken, 10, 1), BadInput);
}

// A ball of radius 8 voxels centred 2 voxels inside the top slice of a 24^3 grid (2 mm voxels) is cut
// by the scan's edge; labelSurface closes it with a flat cap, which withinScan removes: what is left
// lies within the voxel centres, and so do points spread on it. A ball well inside loses nothing.
TEST(WithinScan, DropsTheCapWhereTheScanEndsOnly) {
  GridGeometry g;
  g.size = {24, 24, 24};
  g.spacing = {2, 2, 2};
  g.origin = {-10, 20, 5};
  g.direction = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  auto ball = [&](const Eigen::Vector3d& centre) {
    LabelMap map{Grid<Label>(g), {}};
    for (int k = 0; k < 24; ++k)
      for (int j = 0; j < 24; ++j)
        for (int i = 0; i < 24; ++i)
          if ((Eigen::Vector3d(i, j, k) - centre).norm() <= 8) map.labels.at(i, j, k) = 1;
    return labelSurface(map, 1);
  };
  const TriMesh cut = ball({11.5, 11.5, 21});
  const TriMesh kept = withinScan(cut, g);
  // The cap is a disc of radius sqrt(8^2 - 2^2) = 7.7 voxels, about 750 mm^2 of 2 mm voxels.
  const double removed = area(cut) - area(kept);
  RecordProperty("cap_area_removed_mm2", std::to_string(removed));
  EXPECT_GT(removed, 500.0);
  EXPECT_LT(removed, 1000.0);
  EXPECT_EQ(kept.faceAttributes.integer.at(kLabel).size(), kept.F.rows());
  const MatrixX3d P = spreadSurfacePoints(kept, 100, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) EXPECT_LE(g.worldToIndex(P.row(i).transpose()).z(), 23.0 + 1e-9);

  const TriMesh inside = ball({11.5, 11.5, 11.5});
  EXPECT_EQ(withinScan(inside, g).F.rows(), inside.F.rows());
}

}  // namespace
}  // namespace vesalius::meshing
