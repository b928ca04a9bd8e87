// selfIntersections on constructed surfaces: crossing tetrahedra, a clean sphere, a sphere with a vertex
// pushed through the far side (a fold), triangles that share vertices or an edge, and a random soup
// checked against the all-pairs answer.
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <random>

namespace vesalius {
namespace {

using Pairs = std::vector<std::pair<int, int>>;
using test::sphere;

TriMesh tetSurface(const Eigen::Vector3d& shift) {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.V.rowwise() += shift.transpose();
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

TEST(SelfIntersections, CrossingTetrahedraAreFoundAndOnlyBetweenThem) {
  const TriMesh apart = concatenate(tetSurface({0, 0, 0}), tetSurface({2, 0, 0}));
  EXPECT_TRUE(selfIntersections(apart.V, apart.F).empty());
  const TriMesh crossing = concatenate(tetSurface({0, 0, 0}), tetSurface({0.2, 0.2, 0.2}));
  const Pairs pairs = selfIntersections(crossing.V, crossing.F);
  ASSERT_FALSE(pairs.empty());
  for (const auto& [f, g] : pairs) {
    EXPECT_LT(f, 4);  // one face of each tet: faces of one tet share edges and never cross
    EXPECT_GE(g, 4);
  }
  // The second tet's corner (0.2,0.2,0.2) is inside the first, its far faces cut the first's slanted face.
  EXPECT_NE(std::find(pairs.begin(), pairs.end(), std::make_pair(3, 5)), pairs.end());
}

TEST(SelfIntersections, ClosedSphereHasNone) {
  const TriMesh m = sphere(4);
  ASSERT_EQ(m.F.rows(), 2048);
  ASSERT_EQ(countEdges(m.F).boundary, 0);
  EXPECT_TRUE(selfIntersections(m.V, m.F).empty());
}

TEST(SelfIntersections, VertexPushedThroughTheSphereIsAFold) {
  TriMesh m = sphere(3);
  m.V.row(4) << 0, 0, -1.5;  // the north pole, pulled through to below the south pole
  const Pairs pairs = selfIntersections(m.V, m.F);
  ASSERT_FALSE(pairs.empty());
  // Every crossing involves a triangle of the pulled vertex.
  for (const auto& [f, g] : pairs)
    EXPECT_TRUE((m.F.row(f).array() == 4).any() || (m.F.row(g).array() == 4).any()) << f << " " << g;
}

TEST(SelfIntersections, SharedEdgeCountsOnlyWhenFoldedFlat) {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, 0, 1;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 1, 0, 3;
  EXPECT_TRUE(selfIntersections(m.V, m.F).empty());  // a 90° hinge
  m.V.row(3) << 0.3, 0.5, 0;                          // folded onto the first triangle
  EXPECT_EQ(selfIntersections(m.V, m.F), Pairs({{0, 1}}));
  m.V.row(3) << 0.3, -0.5, 0;  // flat, on the other side: a plane, no overlap
  EXPECT_TRUE(selfIntersections(m.V, m.F).empty());
}

TEST(SelfIntersections, SharedVertexCountsOnlyBeyondIt) {
  TriMesh m;
  m.V.resize(5, 3);
  m.V << 0, 0, 0, 1, -0.5, 0, 1, 0.5, 0, 1, 0, -0.5, 1, 0, 0.5;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 3, 4;  // two triangles from the origin that cross along the x axis
  EXPECT_EQ(selfIntersections(m.V, m.F), Pairs({{0, 1}}));
  m.V.row(3) << 1, 1, -0.5;  // swung aside: only the shared corner remains in common
  m.V.row(4) << 1, 1, 0.5;
  EXPECT_TRUE(selfIntersections(m.V, m.F).empty());
}

TEST(SelfIntersections, RandomSoupMatchesAllPairs) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> centre(-5, 5), offset(-1, 1);
  TriMesh m;
  m.V.resize(600, 3);
  m.F.resize(200, 3);
  for (int t = 0; t < 200; ++t) {
    const Eigen::Vector3d c(centre(rng), centre(rng), centre(rng));
    for (int k = 0; k < 3; ++k) m.V.row(3 * t + k) = (c + Eigen::Vector3d(offset(rng), offset(rng), offset(rng))).transpose();
    m.F.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
  }
  Pairs expected;
  auto p = [&](int v) { return Eigen::Vector3d(m.V.row(v).transpose()); };
  for (int f = 0; f < 200; ++f)
    for (int g = f + 1; g < 200; ++g)
      if (trianglesIntersect(p(3 * f), p(3 * f + 1), p(3 * f + 2), p(3 * g), p(3 * g + 1), p(3 * g + 2)))
        expected.emplace_back(f, g);
  ASSERT_GT(expected.size(), 10u);
  EXPECT_EQ(selfIntersections(m.V, m.F), expected);

  // Restricted to candidates: exactly the pairs with one of them, each once.
  std::vector<int> candidates;
  for (int f = 0; f < 200; f += 3) candidates.push_back(f);
  Pairs withCandidate;
  for (const auto& [f, g] : expected)
    if (f % 3 == 0 || g % 3 == 0) withCandidate.emplace_back(f, g);
  ASSERT_LT(withCandidate.size(), expected.size());
  EXPECT_EQ(selfIntersections(m.V, m.F, candidates), withCandidate);
  EXPECT_TRUE(selfIntersections(m.V, m.F, {}).empty());
  EXPECT_THROW(selfIntersections(m.V, m.F, {200}), UsageError);
}

TEST(SelfIntersections, CoplanarOverlapAndSeparation) {
  const Eigen::Vector3d a0(0, 0, 0), a1(2, 0, 0), a2(0, 2, 0);
  EXPECT_TRUE(trianglesIntersect(a0, a1, a2, {0.2, 0.2, 0}, {0.5, 0.2, 0}, {0.2, 0.5, 0}));  // inside
  EXPECT_TRUE(trianglesIntersect(a0, a1, a2, {1, 1, 0}, {3, 1, 0}, {1, 3, 0}));              // touching at (1,1)
  EXPECT_FALSE(trianglesIntersect(a0, a1, a2, {1.1, 1.1, 0}, {3, 1, 0}, {1, 3, 0}));
  EXPECT_FALSE(trianglesIntersect(a0, a1, a2, {0.2, 0.2, 0.1}, {0.5, 0.2, 0.1}, {0.2, 0.5, 0.1}));  // parallel
}

}  // namespace
}  // namespace vesalius
