// TriangleTree against brute force over every triangle, on a closed torus and on a random soup.
#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace vesalius {
namespace {

// A torus around z (major radius R, minor radius r), nu by nv quads split into triangles.
TriMesh torus(double R, double r, int nu, int nv) {
  TriMesh m;
  m.V.resize(nu * nv, 3);
  m.F.resize(2 * nu * nv, 3);
  const double twoPi = 2.0 * M_PI;
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      const double u = twoPi * i / nu, v = twoPi * j / nv;
      m.V.row(i * nv + j) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
          r * std::sin(v);
      const int a = i * nv + j, b = ((i + 1) % nu) * nv + j, c = ((i + 1) % nu) * nv + (j + 1) % nv,
                d = i * nv + (j + 1) % nv;
      m.F.row(2 * a) << a, b, c;
      m.F.row(2 * a + 1) << a, c, d;
    }
  }
  return m;
}

TriMesh triangleSoup(int count, std::mt19937& rng) {
  std::uniform_real_distribution<double> center(-10.0, 10.0), offset(-1.5, 1.5);
  TriMesh m;
  m.V.resize(3 * count, 3);
  m.F.resize(count, 3);
  for (int t = 0; t < count; ++t) {
    const Eigen::Vector3d c(center(rng), center(rng), center(rng));
    for (int k = 0; k < 3; ++k)
      m.V.row(3 * t + k) = (c + Eigen::Vector3d(offset(rng), offset(rng), offset(rng))).transpose();
    m.F.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
  }
  return m;
}

MatrixX3d randomPoints(int count, double lo, double hi, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(lo, hi);
  MatrixX3d P(count, 3);
  for (int i = 0; i < count; ++i) P.row(i) << u(rng), u(rng), u(rng);
  return P;
}

double bruteForceSquaredDistance(const TriMesh& m, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (int f = 0; f < m.F.rows(); ++f) {
    Eigen::Vector3d w;
    const Eigen::Vector3d q =
        closestPointOnTriangle(p, m.V.row(m.F(f, 0)).transpose(), m.V.row(m.F(f, 1)).transpose(),
                               m.V.row(m.F(f, 2)).transpose(), w);
    best = std::min(best, (p - q).squaredNorm());
  }
  return best;
}

// Every answer: the distance equals brute force, and point, face and weights agree with each other.
void expectMatchesBruteForce(const TriMesh& m, const MatrixX3d& P) {
  const TriangleTree tree(m.V, m.F);
  const std::vector<ClosestPoint> batch = tree.closest(P);
  ASSERT_EQ(batch.size(), size_t(P.rows()));
  for (int i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    const ClosestPoint& c = batch[i];
    ASSERT_GE(c.face, 0);
    ASSERT_LT(c.face, m.F.rows());
    EXPECT_NEAR(std::sqrt(c.squaredDistance), std::sqrt(bruteForceSquaredDistance(m, p)), 1e-12)
        << "point " << i;
    EXPECT_NEAR((p - c.point).squaredNorm(), c.squaredDistance, 1e-12);
    Eigen::Vector3d fromWeights = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) fromWeights += c.barycentric[k] * m.V.row(m.F(c.face, k)).transpose();
    EXPECT_NEAR((fromWeights - c.point).norm(), 0.0, 1e-12);
    EXPECT_NEAR(c.barycentric.sum(), 1.0, 1e-12);
    EXPECT_GE(c.barycentric.minCoeff(), -1e-12);
    // The parallel batch gives exactly what one query gives.
    const ClosestPoint single = tree.closest(p);
    EXPECT_EQ(single.face, c.face);
    EXPECT_EQ(single.squaredDistance, c.squaredDistance);
  }
}

TEST(TriangleTree, TorusMatchesBruteForce) {
  std::mt19937 rng(7);
  const TriMesh m = torus(20.0, 6.0, 72, 36);
  expectMatchesBruteForce(m, randomPoints(2000, -30.0, 30.0, rng));
}

TEST(TriangleTree, TorusVerticesAndFarPointsMatchBruteForce) {
  std::mt19937 rng(8);
  const TriMesh m = torus(20.0, 6.0, 40, 20);
  MatrixX3d P(m.V.rows() + 200, 3);
  P.topRows(m.V.rows()) = m.V;
  P.bottomRows(200) = randomPoints(200, -500.0, 500.0, rng);
  expectMatchesBruteForce(m, P);
  const TriangleTree tree(m.V, m.F);
  for (int v = 0; v < m.V.rows(); ++v)
    EXPECT_EQ(tree.closest(Eigen::Vector3d(m.V.row(v).transpose())).squaredDistance, 0.0);
}

TEST(TriangleTree, RandomSoupMatchesBruteForce) {
  std::mt19937 rng(11);
  const TriMesh m = triangleSoup(3000, rng);
  expectMatchesBruteForce(m, randomPoints(2000, -14.0, 14.0, rng));
}

TEST(TriangleTree, SingleTriangle) {
  MatrixX3d V(3, 3);
  V << 0, 0, 0, 4, 0, 0, 0, 4, 0;
  MatrixX3i F(1, 3);
  F << 0, 1, 2;
  const ClosestPoint c = TriangleTree(V, F).closest(Eigen::Vector3d(1, 1, 5));
  EXPECT_EQ(c.face, 0);
  EXPECT_NEAR((c.point - Eigen::Vector3d(1, 1, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((c.barycentric - Eigen::Vector3d(0.5, 0.25, 0.25)).norm(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(c.squaredDistance, 25.0);
}

TEST(TriangleTree, RejectsEmptyAndBrokenMeshes) {
  MatrixX3d V(3, 3);
  V.setZero();
  EXPECT_THROW(TriangleTree(V, MatrixX3i(0, 3)), BadInput);
  MatrixX3i F(1, 3);
  F << 0, 1, 3;
  EXPECT_THROW(TriangleTree(V, F), BadInput);
}

// Each Voronoi region of Ericson's test: vertices, edges and the face.
TEST(TriangleTree, ClosestPointOnTriangleRegions) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  struct Case {
    Eigen::Vector3d p, point, weights;
  };
  const Case cases[] = {
      {{-1, -1, 1}, {0, 0, 0}, {1, 0, 0}},      {{3, -1, 0}, {2, 0, 0}, {0, 1, 0}},
      {{-1, 3, 2}, {0, 2, 0}, {0, 0, 1}},       {{0.5, -3, 1}, {0.5, 0, 0}, {0.75, 0.25, 0}},
      {{-2, 1.5, 0}, {0, 1.5, 0}, {0.25, 0, 0.75}}, {{2, 2, -1}, {1, 1, 0}, {0, 0.5, 0.5}},
      {{0.5, 0.5, -3}, {0.5, 0.5, 0}, {0.5, 0.25, 0.25}},
  };
  for (const Case& k : cases) {
    Eigen::Vector3d w;
    const Eigen::Vector3d q = closestPointOnTriangle(k.p, a, b, c, w);
    EXPECT_NEAR((q - k.point).norm(), 0.0, 1e-15) << k.p.transpose();
    EXPECT_NEAR((w - k.weights).norm(), 0.0, 1e-15) << k.p.transpose();
  }
}

TEST(TriangleTree, ClosestPointOnDegenerateTriangles) {
  Eigen::Vector3d w;
  // Collinear: the nearest point of the segment from (0,0,0) to (4,0,0).
  const Eigen::Vector3d a(0, 0, 0), b(4, 0, 0), c(1, 0, 0);
  Eigen::Vector3d q = closestPointOnTriangle(Eigen::Vector3d(3, 2, 0), a, b, c, w);
  EXPECT_NEAR((q - Eigen::Vector3d(3, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((w[0] * a + w[1] * b + w[2] * c - q).norm(), 0.0, 1e-15);
  EXPECT_TRUE(w.allFinite());
  // All three corners at one point.
  q = closestPointOnTriangle(Eigen::Vector3d(1, 1, 1), a, a, a, w);
  EXPECT_EQ(q, a);
  EXPECT_NEAR(w.sum(), 1.0, 1e-15);
}

}  // namespace
}  // namespace vesalius
