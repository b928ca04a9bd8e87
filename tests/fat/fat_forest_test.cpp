// FatForest (Dicko et al. 2013, §5) against thicknesses known in closed form: flat and tilted slabs, a spherical
// shell, the exact 26-neighbour path length from one source, and fat that touches no skin.
#include "vesalius/core/error.h"
#include "vesalius/fat/fat_forest.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <tuple>

namespace vesalius::fat {
namespace {

// The worst-case ratio of a 26-neighbour path to the straight line: |w| with w = (1, √2−1, √3−√2)
// (fat_forest.h). Computed, not typed in.
double chamferBound() {
  const Eigen::Vector3d w(1, std::sqrt(2.0) - 1, std::sqrt(3.0) - std::sqrt(2.0));
  return w.norm();
}

GridGeometry grid(Eigen::Vector3i size, Eigen::Vector3d spacing,
                  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity()) {
  GridGeometry g;
  g.size = size;
  g.spacing = spacing;
  g.direction = direction;
  g.origin = Eigen::Vector3d(-12, 30, 7);
  return g;
}

// Skin and fat masks from a classifier of voxel index: 2 skin, 1 fat, 0 other.
std::pair<Mask, Mask> masks(const GridGeometry& g, const std::function<int(int, int, int)>& kind) {
  Mask skin(g, 0), fat(g, 0);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const int c = kind(i, j, k);
        skin.at(i, j, k) = c == 2;
        fat.at(i, j, k) = c == 1;
      }
  return {skin, fat};
}

std::vector<float> skinThicknesses(const FatForest& f, const std::function<bool(int, int, int)>& keep) {
  std::vector<float> t;
  const GridGeometry& g = f.geometry();
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        if (f.isSkin(g.linearIndex(i, j, k)) && keep(i, j, k)) t.push_back(f.thickness().at(i, j, k));
  return t;
}

TEST(FatForest, FlatSlabOnAnAnisotropicObliqueGridHasItsThicknessExactly) {
  // Rotated grid: distances are world distances, so the rotation must not change them.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const GridGeometry g = grid({20, 18, 12}, {0.7, 1.3, 2.2}, R);
  const int fatLayers = 6;  // k = 4..9 under the skin plane k = 10
  const auto [skin, fat] = masks(g, [](int, int, int k) { return k == 10 ? 2 : (k >= 4 && k < 10 ? 1 : 0); });
  const FatForest f(skin, fat);
  const std::vector<float> t = skinThicknesses(f, [](int, int, int) { return true; });
  ASSERT_EQ(t.size(), 20u * 18u);
  for (float x : t) EXPECT_NEAR(x, fatLayers * 2.2, 1e-4);
  EXPECT_EQ(f.statistics().reachedFatVoxels, 20 * 18 * fatLayers);
  EXPECT_EQ(f.statistics().skinVoxelsWithFat, 20 * 18);
  // Off the skin the thickness image is 0.
  EXPECT_EQ(f.thickness().at(3, 3, 5), 0.0f);
  EXPECT_EQ(f.thickness().at(3, 3, 11), 0.0f);
}

TEST(FatForest, ExactTwentySixNeighbourDistanceFromOneSourceAndItsBound) {
  const double s = 1.5;
  const GridGeometry g = grid({13, 13, 13}, {s, s, s});
  const auto [skin, fat] = masks(g, [](int i, int j, int k) { return i + j + k == 0 ? 2 : 1; });
  const FatForest f(skin, fat);
  double worst = 0;
  for (int k = 0; k < 13; ++k)
    for (int j = 0; j < 13; ++j)
      for (int i = 0; i < 13; ++i) {
        if (i + j + k == 0) continue;
        double a[3] = {double(i), double(j), double(k)};
        std::sort(a, a + 3, std::greater<double>());
        const double exact = s * ((a[0] - a[1]) + (a[1] - a[2]) * std::sqrt(2.0) + a[2] * std::sqrt(3.0));
        const double d = f.distance()[g.linearIndex(i, j, k)];
        ASSERT_NEAR(d, exact, 1e-4 * exact) << i << ' ' << j << ' ' << k;
        worst = std::max(worst, d / (s * Eigen::Vector3d(i, j, k).norm()));
      }
  // Near the worst direction (1, 0.414, 0.318) the overestimate approaches 12.8 %, never beyond.
  EXPECT_NEAR(chamferBound(), 1.12809, 1e-5);
  EXPECT_LE(worst, chamferBound() + 1e-6);
  EXPECT_GT(worst, 1.125);
  // Thickness of the one skin voxel: the farthest corner, 12 3-D diagonal steps.
  EXPECT_NEAR(f.thickness().at(0, 0, 0), 12 * s * std::sqrt(3.0), 1e-4);
}

// A skin plane (a band one unit deep along n) and a fat layer of perpendicular thickness h beneath it, on
// a cubic grid of N³ unit voxels. depth(x) = −n·(x − c): skin 0 <= depth < 1, fat 1 <= depth < 1 + h.
struct TiltedSlab {
  int N = 64;
  GridGeometry g;
  Eigen::Vector3d n, c;
  Mask skin, fat;
  double depth(std::int64_t v) const {
    const Eigen::Vector3d x(double(v % N), double((v / N) % N), double(v / (N * N)));
    return -n.dot(x - c);
  }
  TiltedSlab(const Eigen::Vector3d& normal, double h) {
    g = grid({N, N, N}, {1, 1, 1});
    g.origin.setZero();
    n = normal.normalized();
    c = Eigen::Vector3d::Constant(N / 2.0);
    std::tie(skin, fat) = masks(g, [&](int i, int j, int k) {
      const double s = depth(g.linearIndex(i, j, k));
      return s >= 0 && s < 1 ? 2 : (s >= 1 && s < 1 + h ? 1 : 0);
    });
  }
  // Skin voxels whose trees the grid's edge cannot cut.
  bool interior(int i, int j, int k, double h) const {
    const double margin = 1.2 * h + 2;
    return std::min({i, j, k}) > margin && std::max({i, j, k}) < N - 1 - margin;
  }
};

TEST(FatForest, TiltedSlabThicknessIsTheLayerThicknessPlusAtMostAVoxel) {
  const double h = 8;
  for (const Eigen::Vector3d& normal : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0.2, 0.1),
                                        Eigen::Vector3d(0.3, -1, 0.45)}) {
    SCOPED_TRACE(normal.transpose());
    const TiltedSlab slab(normal, h);
    const FatForest f(slab.skin, slab.fat);
    const std::vector<float> t = skinThicknesses(f, [&](int i, int j, int k) { return slab.interior(i, j, k, h); });
    ASSERT_GT(t.size(), 50u);
    // Skin centre to deepest fat centre is between h and h + 1 deep (both bands are one unit deep), and
    // a 26-neighbour path is at most |w| times longer than the straight line.
    for (float x : t) {
      EXPECT_GE(x, h - 1e-4);
      EXPECT_LE(x, chamferBound() * (h + 1));
    }
    // The paper's per-tree value alone leaves many skin voxels of the staircase with almost nothing.
    std::vector<float> tree;
    for (std::int64_t v = 0; v < slab.g.voxelCount(); ++v)
      if (slab.skin.values[v]) tree.push_back(f.treeThickness().values[v]);
    const double shallow = double(std::count_if(tree.begin(), tree.end(), [&](float x) { return x < h / 2; }));
    std::cout << "tilted " << normal.transpose() << ": tree thickness < h/2 at " << shallow / tree.size() << '\n';
    if (normal.z() != 1) {
      EXPECT_GT(shallow / tree.size(), 0.2);
    } else {
      EXPECT_EQ(shallow, 0);
    }
  }
}

TEST(FatForest, DistanceOverestimatesTheDepthByTheTwentySixNeighbourBoundAtWorst) {
  // Along the worst direction w every step type gains depth at the same rate 1/|w| per mm, so the path
  // from the skin to a fat voxel at depth D is |w| times longer than the straight line.
  const double h = 20;
  const Eigen::Vector3d w(1, std::sqrt(2.0) - 1, std::sqrt(3.0) - std::sqrt(2.0));
  const TiltedSlab slab(w, h);
  const FatForest f(slab.skin, slab.fat);
  int deep = 0;
  double ratio = 0;
  for (std::int64_t v = 0; v < slab.g.voxelCount(); ++v) {
    if (!slab.fat.values[v]) continue;
    const int i = int(v % 64), j = int((v / 64) % 64), k = int(v / 4096);
    if (!slab.interior(i, j, k, 0.5 * h)) continue;
    const double depth = slab.depth(v);  // the skin voxels lie at depths 0..1
    const double d = f.distance()[v];
    EXPECT_GE(d, chamferBound() * (depth - 1) - 1e-3);
    EXPECT_LE(d, chamferBound() * depth + 1e-3);
    if (depth > 15) {
      ++deep;
      ratio += d / depth;
    }
  }
  ASSERT_GT(deep, 100);
  // At least |w| (D − 1) / D, 1.065 at D = 18: really longer than the straight line.
  EXPECT_GT(ratio / deep, 1.05);
  EXPECT_LT(ratio / deep, chamferBound());
}

TEST(FatForest, SphericalShellThicknessIsTheShellWidth) {
  const int N = 71;
  const double R = 32, width = 10;  // skin R-1.5 < r <= R, fat R-1.5-width < r <= R-1.5
  const GridGeometry g = grid({N, N, N}, {1, 1, 1});
  const Eigen::Vector3d c(35.2, 34.9, 35.1);
  const auto [skin, fat] = masks(g, [&](int i, int j, int k) {
    const double r = (Eigen::Vector3d(i, j, k) - c).norm();
    return r <= R && r > R - 1.5 ? 2 : (r <= R - 1.5 && r > R - 1.5 - width ? 1 : 0);
  });
  const FatForest f(skin, fat);
  const std::vector<float> t = skinThicknesses(f, [](int, int, int) { return true; });
  // Skin centre to deepest fat centre is the width within a voxel diagonal, read up to |w| longer.
  // Convex skin: the fat under it converges (the shell's inner face has 41 % of the skin's area), so a
  // few skin voxels own no deep voxel even after gathering: the lower tail is short of the width.
  std::vector<float> q = t;
  std::sort(q.begin(), q.end());
  auto quantile = [&](double p) { return q[std::size_t(p * double(q.size() - 1))]; };
  EXPECT_GT(quantile(0.05), width / 2);
  EXPECT_GE(quantile(0.25), width - std::sqrt(3.0));
  EXPECT_GT(quantile(0.5), width - 1);
  EXPECT_LT(quantile(0.5), 1.07 * width + 1);
  EXPECT_LE(quantile(1.0), chamferBound() * (width + std::sqrt(3.0)));
  // The shell is connected to the skin all round: every fat voxel is reached.
  EXPECT_EQ(f.statistics().reachedFatVoxels, f.statistics().fatVoxels);
}

TEST(FatForest, FatThatTouchesNoSkinHasNoRootAndAddsNothing) {
  const GridGeometry g = grid({30, 30, 30}, {1, 1, 1});
  // Skin plane k = 29, fat k = 25..28; a blob of fat at k = 5..10 separated by soft tissue.
  const auto [skin, fat] = masks(g, [](int i, int j, int k) {
    if (k == 29) return 2;
    if (k >= 25) return 1;
    return (k >= 5 && k <= 10 && i > 10 && i < 20 && j > 10 && j < 20) ? 1 : 0;
  });
  const FatForest f(skin, fat);
  const std::int64_t blob = g.linearIndex(15, 15, 7);
  EXPECT_EQ(f.root()[blob], -1);
  EXPECT_EQ(f.parent()[blob], -1);
  EXPECT_TRUE(std::isinf(f.distance()[blob]));
  EXPECT_TRUE(f.pathToRoot(blob).empty());
  EXPECT_EQ(f.statistics().fatVoxels - f.statistics().reachedFatVoxels, 9 * 9 * 6);
  EXPECT_NEAR(f.thickness().at(15, 15, 29), 4.0, 1e-5);
}

TEST(FatForest, PathsAreWalkableFromAnyFatVoxelToItsRoot) {
  const GridGeometry g = grid({24, 20, 16}, {0.8, 1.1, 1.7});
  const auto [skin, fat] = masks(g, [](int i, int j, int k) {
    if (k == 15) return 2;
    return k >= 15 - 1 - (i + j) / 4 ? 1 : 0;  // fat deepening with i + j
  });
  const FatForest f(skin, fat);
  const Eigen::Matrix3d M = g.direction * g.spacing.asDiagonal();
  for (std::int64_t v = 0; v < g.voxelCount(); ++v) {
    if (!fat.values[v]) continue;
    const std::vector<std::int32_t> path = f.pathToRoot(v);
    ASSERT_FALSE(path.empty());
    EXPECT_EQ(path.back(), f.root()[v]);
    EXPECT_TRUE(skin.values[path.back()]);
    double length = 0;
    for (std::size_t p = 1; p < path.size(); ++p) {
      auto ijk = [&](std::int64_t w) {
        return Eigen::Vector3d(double(w % 24), double((w / 24) % 20), double(w / (24 * 20)));
      };
      const Eigen::Vector3d step = ijk(path[p]) - ijk(path[p - 1]);
      ASSERT_LE(step.cwiseAbs().maxCoeff(), 1.0);
      length += (M * step).norm();
    }
    EXPECT_NEAR(length, f.distance()[v], 1e-4);
    // Never shorter than the straight line to the root.
    EXPECT_GE(f.distance()[v] + 1e-4, (M * (Eigen::Vector3d(double(v % 24), double((v / 24) % 20),
                                                               double(v / (24 * 20))) -
                                             Eigen::Vector3d(double(path.back() % 24),
                                                             double((path.back() / 24) % 20),
                                                             double(path.back() / (24 * 20)))))
                                           .norm());
  }
}

TEST(FatForest, MismatchedGridsAndEmptySkinAreBadInput) {
  const GridGeometry a = grid({8, 8, 8}, {1, 1, 1});
  GridGeometry b = a;
  b.spacing.x() = 1.5;
  Mask skin(a, 1), fat(b, 1), none(a, 0);
  try {
    FatForest f(skin, fat, {}, "labels.nii.gz");
    ADD_FAILURE() << "accepted";
  } catch (const BadInput& e) {
    EXPECT_STREQ(e.what(), "labels.nii.gz: skin and fat masks are on different grids");
  }
  try {
    FatForest f(none, none, {}, "labels.nii.gz");
    ADD_FAILURE() << "accepted";
  } catch (const BadInput& e) {
    EXPECT_STREQ(e.what(), "labels.nii.gz: the skin mask is empty");
  }
}

TEST(FatForest, MaxDistanceLeavesDeeperFatUnreached) {
  const GridGeometry g = grid({6, 6, 20}, {1, 1, 1});
  const auto [skin, fat] = masks(g, [](int, int, int k) { return k == 19 ? 2 : 1; });
  FatForestOptions options;
  options.maxDistanceMm = 7.5;
  const FatForest f(skin, fat, options);
  EXPECT_NEAR(f.thickness().at(3, 3, 19), 7.0, 1e-5);
  EXPECT_EQ(f.statistics().reachedFatVoxels, 6 * 6 * 7);
}

}  // namespace
}  // namespace vesalius::fat
