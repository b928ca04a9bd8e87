// Small pieces of a mask cleared (small_pieces.h): pieces joined by a corner count as one, pieces on the
// grid's border are measured whole, kept voxels become 1, and on random masks the result is what a
// union-find over all 26 neighbours keeps.
#include "vesalius/core/small_pieces.h"

#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <numeric>
#include <random>
#include <vector>

namespace vesalius {
namespace {

Grid<std::uint8_t> emptyMask(int nx, int ny, int nz) {
  GridGeometry g;
  g.size = {nx, ny, nz};
  return Grid<std::uint8_t>(g, 0);
}

TEST(SmallPieces, CornerNeighboursJoinAndBorderPiecesAreWhole) {
  Grid<std::uint8_t> m = emptyMask(7, 6, 5);
  m.at(2, 2, 2) = m.at(3, 3, 3) = 1;                // two voxels meeting at a corner: one piece of 2
  m.at(0, 0, 0) = m.at(1, 0, 0) = 1;  // three in the grid's corner, one of another nonzero value
  m.at(0, 1, 0) = 7;
  m.at(6, 5, 4) = 1;                                // one alone in the opposite corner
  EXPECT_EQ(dropSmallPieces(m, 3), 3);
  EXPECT_EQ(m.at(2, 2, 2) + m.at(3, 3, 3) + m.at(6, 5, 4), 0);
  EXPECT_EQ(m.at(0, 0, 0) + m.at(1, 0, 0) + m.at(0, 1, 0), 3);  // a piece of exactly minVoxels stays, as 1s
  EXPECT_EQ(dropSmallPieces(m, 4), 3);
  EXPECT_EQ(std::accumulate(m.values.begin(), m.values.end(), 0), 0);
  EXPECT_EQ(dropSmallPieces(m, 1), 0);
}

// Union-find over all 26 neighbours, then pieces under minVoxels cleared.
Grid<std::uint8_t> byUnionFind(Grid<std::uint8_t> m, long minVoxels) {
  const GridGeometry& g = m.geometry;
  std::vector<std::int64_t> parent(m.values.size());
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<std::int64_t(std::int64_t)> root = [&](std::int64_t x) {
    return parent[std::size_t(x)] == x ? x : parent[std::size_t(x)] = root(parent[std::size_t(x)]);
  };
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        if (!m.at(i, j, k)) continue;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              if (g.contains(i + dx, j + dy, k + dz) && m.at(i + dx, j + dy, k + dz))
                parent[std::size_t(root(g.linearIndex(i, j, k)))] = root(g.linearIndex(i + dx, j + dy, k + dz));
      }
  std::vector<long> size(m.values.size(), 0);
  for (std::size_t n = 0; n < m.values.size(); ++n)
    if (m.values[n]) ++size[std::size_t(root(std::int64_t(n)))];
  for (std::size_t n = 0; n < m.values.size(); ++n)
    if (m.values[n] && size[std::size_t(root(std::int64_t(n)))] < minVoxels) m.values[n] = 0;
  return m;
}

TEST(SmallPieces, RandomMasksMatchAUnionFind) {
  std::mt19937 random(7);
  for (const double density : {0.05, 0.15, 0.25})
    for (const long minVoxels : {2L, 5L, 40L}) {
      Grid<std::uint8_t> m = emptyMask(17, 13, 11);
      std::bernoulli_distribution on(density);
      for (auto& v : m.values) v = on(random);
      const Grid<std::uint8_t> expected = byUnionFind(m, minVoxels);
      const long before = std::accumulate(m.values.begin(), m.values.end(), 0L);
      const std::int64_t cleared = dropSmallPieces(m, minVoxels);
      std::cout << "density " << density << ", pieces under " << minVoxels << ": " << cleared << " of " << before
                << " voxels cleared\n";
      EXPECT_EQ(m.values, expected.values);
      EXPECT_EQ(before - cleared, std::accumulate(m.values.begin(), m.values.end(), 0L));
    }
}

}  // namespace
}  // namespace vesalius
