// vertexTets and vertexRings on a strip of tets where each ring is known by hand, and bad indices refused.
#include "vesalius/core/error.h"
#include "vesalius/core/tet_adjacency.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace vesalius {
namespace {

// A chain of 6 tets, tet t on vertices t .. t + 3: vertex v lies in tets max(0, v - 3) .. min(v, 5).
MatrixX4i chain() {
  MatrixX4i T(6, 4);
  for (int t = 0; t < 6; ++t) T.row(t) << t, t + 1, t + 2, t + 3;
  return T;
}

TEST(TetAdjacency, TetsOfEachVertexAscending) {
  const VertexTets a = vertexTets(chain(), 9);
  ASSERT_EQ(a.start.size(), 10u);
  EXPECT_EQ(a.tets.size(), 24u);
  for (int v = 0; v < 9; ++v) {
    std::vector<int> expected;
    for (int t = std::max(0, v - 3); t <= std::min(v, 5); ++t) expected.push_back(t);
    EXPECT_EQ(a.of(v), expected) << "vertex " << v;
  }
}

TEST(TetAdjacency, RingsGrowByWholeTetsAndListEachVertexOnce) {
  const MatrixX4i T = chain();
  const VertexTets a = vertexTets(T, 9);
  EXPECT_EQ(vertexRings(T, a, {0, 0}, 0), (std::vector<int>{0}));
  EXPECT_EQ(vertexRings(T, a, {0}, 1), (std::vector<int>{0, 1, 2, 3}));  // tet 0
  std::vector<int> two = vertexRings(T, a, {0}, 2);                      // tets 0 .. 3
  EXPECT_EQ(two.size(), 7u);
  EXPECT_EQ(two.front(), 0);
  std::sort(two.begin(), two.end());
  EXPECT_EQ(two, (std::vector<int>{0, 1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(vertexRings(T, a, {8}, 1), (std::vector<int>{8, 5, 6, 7}));  // tet 5
  EXPECT_EQ(vertexRings(T, a, {4}, 10).size(), 9u);
  EXPECT_TRUE(vertexRings(T, a, {}, 3).empty());
}

TEST(TetAdjacency, RefusesAVertexOutsideTheMesh) {
  EXPECT_THROW(vertexTets(chain(), 8), BadInput);
  MatrixX4i T = chain();
  T(2, 1) = -1;
  EXPECT_THROW(vertexTets(T, 9), BadInput);
}

}  // namespace
}  // namespace vesalius
