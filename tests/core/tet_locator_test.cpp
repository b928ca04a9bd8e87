// TetLocator on a jittered tet grid filling the cube [0, 2]^3: containment inside, nearest point outside.
#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"
#include "vesalius/core/triangle_tree.h"

#include "test_tets.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace vesalius {
namespace {

constexpr double kSide = 2.0;

double signedVolume(const MatrixX3d& V, const Eigen::Vector4i& t) {
  const Eigen::Vector3d a = V.row(t[0]).transpose();
  return (V.row(t[1]).transpose() - a)
             .dot((V.row(t[2]).transpose() - a).cross(V.row(t[3]).transpose() - a)) / 6.0;
}

// n^3 cubes of six Kuhn tets each (test_tets.h). Interior vertices are jittered after orienting, so that
// a tet turned inside out would show as a negative volume; the boundary stays the cube.
TetMesh kuhnGrid(int n, double jitter, std::mt19937& rng) {
  TetMesh m = test::boxTets(n, n, n, kSide / n);
  const int nv = n + 1;
  std::uniform_real_distribution<double> u(-jitter * kSide / n, jitter * kSide / n);
  auto id = [nv](int i, int j, int k) { return i + nv * (j + nv * k); };
  for (int k = 1; k < n; ++k)
    for (int j = 1; j < n; ++j)
      for (int i = 1; i < n; ++i) m.V.row(id(i, j, k)) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  return m;
}

Eigen::Vector3d fromWeights(const TetMesh& m, const TetLocation& loc) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) p += loc.barycentric[k] * m.V.row(m.T(loc.tet, k)).transpose();
  return p;
}

double bruteForceDistance(const TetMesh& m, const Eigen::Vector3d& p) {
  const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double best = std::numeric_limits<double>::infinity();
  for (int t = 0; t < m.T.rows(); ++t)
    for (const auto& f : faces) {
      Eigen::Vector3d w;
      const Eigen::Vector3d q = closestPointOnTriangle(p, m.V.row(m.T(t, f[0])).transpose(),
                                                       m.V.row(m.T(t, f[1])).transpose(),
                                                       m.V.row(m.T(t, f[2])).transpose(), w);
      best = std::min(best, (p - q).norm());
    }
  return best;
}

class TetLocatorGrid : public ::testing::Test {
 protected:
  std::mt19937 rng{5};
  TetMesh mesh = kuhnGrid(6, 0.15, rng);
  TetLocator locator{mesh.V, mesh.T};
};

TEST_F(TetLocatorGrid, AllTetsArePositive) {
  for (int t = 0; t < mesh.T.rows(); ++t) ASSERT_GT(signedVolume(mesh.V, mesh.T.row(t).transpose()), 0.0);
}

TEST_F(TetLocatorGrid, InsidePointsAreReproducedByTheirWeights) {
  std::uniform_real_distribution<double> u(0.0, kSide);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const std::optional<TetLocation> loc = locator.locate(p);
    ASSERT_TRUE(loc.has_value()) << p.transpose();
    EXPECT_GE(loc->barycentric.minCoeff(), -1e-9);
    EXPECT_NEAR(loc->barycentric.sum(), 1.0, 1e-12);
    EXPECT_NEAR((fromWeights(mesh, *loc) - p).norm(), 0.0, 1e-12);
    EXPECT_EQ(loc->barycentric, locator.barycentric(loc->tet, p));
  }
}

TEST_F(TetLocatorGrid, VerticesAndCornersAreInside) {
  for (int v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = mesh.V.row(v).transpose();
    const std::optional<TetLocation> loc = locator.locate(p);
    ASSERT_TRUE(loc.has_value()) << "vertex " << v;
    EXPECT_NEAR((fromWeights(mesh, *loc) - p).norm(), 0.0, 1e-12);
  }
}

TEST_F(TetLocatorGrid, OutsidePointsGetTheNearestPointOfTheMesh) {
  std::uniform_real_distribution<double> u(-1.5, kSide + 1.5);
  MatrixX3d P(500, 3);
  for (int i = 0; i < P.rows();) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    // Keep points clearly outside: the distance to the cube must exceed the locate() tolerance.
    if ((p - p.cwiseMax(0.0).cwiseMin(kSide)).norm() > 1e-6) P.row(i++) = p.transpose();
  }
  const std::vector<TetLocation> batch = locator.locateOrNearest(P);
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    EXPECT_FALSE(locator.locate(p).has_value()) << p.transpose();
    const TetLocation& loc = batch[i];
    ASSERT_GE(loc.tet, 0);
    EXPECT_GE(loc.barycentric.minCoeff(), 0.0);
    EXPECT_LE(loc.barycentric.maxCoeff(), 1.0);
    EXPECT_NEAR(loc.barycentric.sum(), 1.0, 1e-12);
    const Eigen::Vector3d q = fromWeights(mesh, loc);
    EXPECT_NEAR((p - q).norm(), bruteForceDistance(mesh, p), 1e-12);
    // The mesh fills the cube exactly, so its nearest point is the clamped point.
    EXPECT_NEAR((q - p.cwiseMax(0.0).cwiseMin(kSide)).norm(), 0.0, 1e-12);
    EXPECT_EQ(locator.locateOrNearest(p).tet, loc.tet);
  }
}

TEST_F(TetLocatorGrid, InsidePointsInBatchAreLocated) {
  std::uniform_real_distribution<double> u(0.0, kSide);
  MatrixX3d P(300, 3);
  for (int i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), u(rng);
  const std::vector<TetLocation> batch = locator.locateOrNearest(P);
  for (int i = 0; i < P.rows(); ++i) {
    EXPECT_EQ(batch[i].tet, locator.locate(P.row(i).transpose())->tet);
    EXPECT_NEAR((fromWeights(mesh, batch[i]) - P.row(i).transpose()).norm(), 0.0, 1e-12);
  }
}

// The batch visits points in Morton order for speed; each answer must be exactly the single query's.
TEST_F(TetLocatorGrid, BatchAnswersAreTheSingleQueryAnswers) {
  std::uniform_real_distribution<double> u(-0.5, kSide + 0.5);
  MatrixX3d P(3000, 3);
  for (int i = 0; i < P.rows(); ++i) P.row(i) << u(rng), u(rng), u(rng);
  P.row(7) = P.row(2000);  // a repeated point
  const std::vector<TetLocation> batch = locator.locateOrNearest(P);
  int inside = 0;
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    const TetLocation single = locator.locateOrNearest(p);
    ASSERT_EQ(batch[i].tet, single.tet) << i;
    ASSERT_EQ(batch[i].barycentric, single.barycentric) << i;
    ASSERT_EQ(batch[i].inside, locator.locate(p).has_value()) << i;
    inside += batch[i].inside;
  }
  // About (2 / 3)^3 of the points fall in the cube.
  EXPECT_GT(inside, 700);
  EXPECT_LT(inside, 1200);
}

TEST(TetLocator, BarycentricOfTheUnitTet) {
  MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  MatrixX4i T(1, 4);
  T << 0, 1, 2, 3;
  const TetLocator locator(V, T);
  const Eigen::Vector4d w = locator.barycentric(0, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_NEAR((w - Eigen::Vector4d(0.4, 0.1, 0.2, 0.3)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((locator.barycentric(0, Eigen::Vector3d(1, 1, 0)) - Eigen::Vector4d(-1, 1, 1, 0)).norm(),
              0.0, 1e-15);
  EXPECT_FALSE(locator.locate(Eigen::Vector3d(0.5, 0.5, 0.5)).has_value());
  // Within the tolerance, a point a hair outside a face still counts as inside.
  EXPECT_TRUE(locator.locate(Eigen::Vector3d(0.2, 0.2, -1e-12)).has_value());
  const TetLocation nearest = locator.locateOrNearest(Eigen::Vector3d(1, 1, 1));
  EXPECT_NEAR((nearest.barycentric - Eigen::Vector4d(0, 1, 1, 1) / 3.0).norm(), 0.0, 1e-15);
}

TEST(TetLocator, FlatTetsAreNeverReportedAsContaining) {
  TetMesh m;
  m.V.resize(8, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1,  // the unit tet
      5, 0, 0, 6, 0, 0, 5, 1, 0, 6, 1, 0;      // four points in the plane z = 0
  m.T.resize(2, 4);
  m.T << 0, 1, 2, 3, 4, 5, 6, 7;
  const TetLocator locator(m.V, m.T);
  EXPECT_EQ(locator.locate(Eigen::Vector3d(0.1, 0.1, 0.1))->tet, 0);
  EXPECT_FALSE(locator.locate(Eigen::Vector3d(5.5, 0.5, 0.0)).has_value());
  const TetLocation nearest = locator.locateOrNearest(Eigen::Vector3d(5.5, 0.5, 2.0));
  EXPECT_EQ(nearest.tet, 1);
  EXPECT_TRUE(nearest.barycentric.allFinite());
  EXPECT_NEAR((fromWeights(m, nearest) - Eigen::Vector3d(5.5, 0.5, 0)).norm(), 0.0, 1e-12);
}

TEST(TetLocator, RejectsEmptyAndBrokenMeshes) {
  MatrixX3d V = MatrixX3d::Zero(4, 3);
  EXPECT_THROW(TetLocator(V, MatrixX4i(0, 4)), BadInput);
  MatrixX4i T(1, 4);
  T << 0, 1, 2, 4;
  EXPECT_THROW(TetLocator(V, T), BadInput);
}

}  // namespace
}  // namespace vesalius
