// Bounded biharmonic weights on a synthetic bar of two boxes (a thin one and a thick one, joined end to
// end) with a small handle inside each: bounds, partition of unity, handles, monotonicity along the bar,
// and the QP's KKT conditions checked with a Laplacian written here independently of the library.
// Then the fat editor's combination of weights and amounts (bone_fat_thickness.h).
#include "vesalius/core/error.h"
#include "vesalius/fat/bone_fat_thickness.h"
#include "vesalius/fat/bounded_biharmonic_weights.h"

#include <gtest/gtest.h>

#include <iostream>

namespace vesalius::fat {
namespace {

using Index = Eigen::Index;

// x 0..19: a box 8 x 8 voxels across; x 20..43: 12 x 12 across, centred on the same axis. Handles: a
// 2 x 2 x 2 cube in each box, well inside it, so the soft parts beyond them pull the unconstrained
// biharmonic weights out of [0, 1].
Grid<std::int32_t> twoBoxBar(double spacing = 2.0) {
  GridGeometry g;
  g.size = Eigen::Vector3i(44, 14, 14);
  g.spacing = Eigen::Vector3d::Constant(spacing);
  Grid<std::int32_t> labels(g, -1);
  for (int k = 0; k < 14; ++k)
    for (int j = 0; j < 14; ++j)
      for (int i = 0; i < 44; ++i) {
        const int half = i < 20 ? 4 : 6;
        if (std::abs(2 * j - 13) < 2 * half && std::abs(2 * k - 13) < 2 * half) labels.at(i, j, k) = 0;
      }
  for (int k = 6; k <= 7; ++k)
    for (int j = 6; j <= 7; ++j) {
      labels.at(8, j, k) = labels.at(9, j, k) = 1;
      labels.at(32, j, k) = labels.at(33, j, k) = 2;
    }
  return labels;
}

// (L w)(v) over the domain's 6-neighbours, natural boundary, unit weights (isotropic grid).
Eigen::VectorXd laplacian(const BoundedBiharmonicWeights& b, const Eigen::VectorXd& w) {
  const GridGeometry& g = b.geometry;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(w.size());
  for (Index r = 0; r < w.size(); ++r) {
    const std::int64_t v = b.voxel[r];
    const int i = int(v % g.size.x()), j = int(v / g.size.x() % g.size.y()), k = int(v / g.size.x() / g.size.y());
    for (const Eigen::Vector3i& n : {Eigen::Vector3i(i + 1, j, k), Eigen::Vector3i(i - 1, j, k), Eigen::Vector3i(i, j + 1, k),
                                     Eigen::Vector3i(i, j - 1, k), Eigen::Vector3i(i, j, k + 1), Eigen::Vector3i(i, j, k - 1)}) {
      if (!g.contains(n.x(), n.y(), n.z())) continue;
      const std::int32_t c = b.row[g.linearIndex(n.x(), n.y(), n.z())];
      if (c >= 0) out[r] += w[c] - w[r];
    }
  }
  return out;
}

TEST(BoundedBiharmonicWeights, TwoBoxBarWeightsAreBoundedSumToOneAndEqualOneOnTheirHandle) {
  const Grid<std::int32_t> labels = twoBoxBar();
  const BoundedBiharmonicWeights b = boundedBiharmonicWeights(labels, 2);
  ASSERT_EQ(b.W.rows(), Index(20 * 64 + 24 * 144));
  EXPECT_EQ(b.unreachable, 0);
  std::cout << "iterations " << b.iterations[0] << ", " << b.iterations[1] << "; at 0: " << b.atZero[0] << ", "
            << b.atZero[1] << "; at 1: " << b.atOne[0] << ", " << b.atOne[1] << "; max |sum - 1| before normalising "
            << b.maxSumDeviation << "\n";
  EXPECT_GE(b.raw.minCoeff(), -1e-9);
  EXPECT_LE(b.raw.maxCoeff(), 1 + 1e-9);
  EXPECT_GE(b.W.minCoeff(), -1e-9);
  EXPECT_LE(b.W.maxCoeff(), 1 + 1e-9);
  EXPECT_LT((b.W.rowwise().sum().array() - 1).abs().maxCoeff(), 1e-12);
  // Two handles: w ↦ 1 − w maps one handle's QP onto the other's, so the raw weights already sum to 1.
  EXPECT_LT(b.maxSumDeviation, 1e-8);
  for (Index r = 0; r < b.W.rows(); ++r) {
    const std::int32_t l = labels.values[b.voxel[r]];
    if (l > 0) {
      EXPECT_EQ(b.W(r, l - 1), 1.0);
    }
  }
}

TEST(BoundedBiharmonicWeights, TwoBoxBarWeightIsMonotoneAlongTheBar) {
  const Grid<std::int32_t> labels = twoBoxBar();
  const BoundedBiharmonicWeights b = boundedBiharmonicWeights(labels, 2);
  // Along the axis line through both handles, and the mean over each cross-section, from one handle to
  // the other: handle 0's weight never rises.
  for (int k = 6; k <= 7; ++k)
    for (int j = 6; j <= 7; ++j)
      for (int i = 9; i < 33; ++i) {
        const double here = b.W(b.row[labels.geometry.linearIndex(i, j, k)], 0);
        const double next = b.W(b.row[labels.geometry.linearIndex(i + 1, j, k)], 0);
        EXPECT_LE(next, here + 1e-9) << i;
      }
  std::vector<double> mean(44, 0.0), count(44, 0.0);
  for (Index r = 0; r < b.W.rows(); ++r) {
    const int i = int(b.voxel[r] % 44);
    mean[i] += b.W(r, 0), count[i] += 1;
  }
  for (int i = 9; i < 33; ++i) EXPECT_LE(mean[i + 1] / count[i + 1], mean[i] / count[i] + 1e-9) << i;
  EXPECT_GT(mean[9] / count[9], 0.9);
  EXPECT_LT(mean[33] / count[33], 0.1);
}

// KKT of min ½ Σ (L w)² with w fixed on the handles, 0 <= w <= 1: the gradient g = L (L w) is 0 where a
// free voxel's weight is inside (0, 1), >= 0 where it is 0, <= 0 where it is 1.
TEST(BoundedBiharmonicWeights, TwoBoxBarSolutionMeetsTheKktConditions) {
  const Grid<std::int32_t> labels = twoBoxBar();
  const BoundedBiharmonicWeights b = boundedBiharmonicWeights(labels, 2);
  for (int h = 0; h < 2; ++h) {
    const Eigen::VectorXd w = b.raw.col(h);
    const Eigen::VectorXd g = laplacian(b, laplacian(b, w));
    const double scale = g.cwiseAbs().maxCoeff();
    int inside = 0, atZero = 0, atOne = 0;
    for (Index r = 0; r < w.size(); ++r) {
      if (labels.values[b.voxel[r]] != 0) continue;
      if (w[r] == 0) {
        EXPECT_GE(g[r], -1e-9) << r;
        ++atZero;
      } else if (w[r] == 1) {
        EXPECT_LE(g[r], 1e-9) << r;
        ++atOne;
      } else {
        EXPECT_LT(std::abs(g[r]), 1e-9) << r;
        ++inside;
      }
    }
    std::cout << "handle " << h << ": " << inside << " inside, " << atZero << " at 0, " << atOne << " at 1; max |g| "
              << scale << ", KKT residual " << b.kktResidual[h] << " after " << b.iterations[h] << " iterations\n";
    // The bounds bind: the unconstrained weights overshoot beyond the handles, so the test checks signs.
    EXPECT_GT(atZero + atOne, 50);
    EXPECT_EQ(atZero, b.atZero[h]);
    EXPECT_EQ(atOne, b.atOne[h]);
    EXPECT_LE(b.kktResidual[h], 1e-10);
  }
}

// Without the active set method (maxActiveSetIterations = 0), the fallback that guarantees termination,
// projected Newton, reaches the same weights on a smaller bar.
TEST(BoundedBiharmonicWeights, ProjectedNewtonFallbackReachesTheActiveSetSolution) {
  GridGeometry g;
  g.size = Eigen::Vector3i(24, 6, 6);
  Grid<std::int32_t> labels(g, 0);
  labels.at(6, 2, 2) = labels.at(6, 3, 3) = 1;
  labels.at(18, 2, 3) = labels.at(18, 3, 2) = 2;
  const BoundedBiharmonicWeights a = boundedBiharmonicWeights(labels, 2);
  BoundedBiharmonicOptions o;
  o.maxActiveSetIterations = 0;
  const BoundedBiharmonicWeights p = boundedBiharmonicWeights(labels, 2, o);
  std::cout << "active set: " << a.iterations[0] << " iterations; projected Newton: " << p.iterations[0]
            << ", KKT residual " << p.kktResidual[0] << "; max |difference| " << (a.raw - p.raw).cwiseAbs().maxCoeff() << "\n";
  EXPECT_FALSE(a.projectedNewton[0]);
  EXPECT_TRUE(p.projectedNewton[0]);
  EXPECT_GT(a.atZero[0] + a.atOne[0], 0);
  EXPECT_LE(p.kktResidual[0], 1e-10);
  EXPECT_LT((a.raw - p.raw).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(BoundedBiharmonicWeights, BadLabelsAndOptionsAreUsageErrors) {
  Grid<std::int32_t> labels = twoBoxBar();
  EXPECT_THROW(boundedBiharmonicWeights(labels, 3), UsageError);  // handle 2 has no voxel
  EXPECT_THROW(boundedBiharmonicWeights(labels, 0), UsageError);
  labels.at(0, 7, 7) = 5;
  EXPECT_THROW(boundedBiharmonicWeights(labels, 2), UsageError);
  BoundedBiharmonicOptions o;
  o.tolerance = 0;
  EXPECT_THROW(boundedBiharmonicWeights(twoBoxBar(), 2, o), UsageError);
}

TEST(BoneFatThickness, LinearInTheAmountsAndFullOnAHandle) {
  const Grid<std::int32_t> labels = twoBoxBar(2.0);
  const BoundedBiharmonicWeights b = boundedBiharmonicWeights(labels, 2);
  const GridGeometry& g = labels.geometry;
  MatrixX3d P(4, 3);
  P.row(0) = g.indexToWorld(Eigen::Vector3d(8.5, 6.5, 6.5)).transpose();   // the middle of handle 0
  P.row(1) = g.indexToWorld(Eigen::Vector3d(20.3, 6.5, 4.2)).transpose();  // between the boxes
  P.row(2) = g.indexToWorld(Eigen::Vector3d(43.5, 6.5, 6.5)).transpose();  // on the bar's end face
  P.row(3) = g.indexToWorld(Eigen::Vector3d(10.0, 1.0, 1.0)).transpose();  // outside the thin box
  const Eigen::Vector2d amounts(0.4, 0.1);
  const BoneFatThickness t = boneFatThickness(b, P, amounts);
  const BoneFatThickness t2 = boneFatThickness(b, P, 2 * amounts);
  EXPECT_NEAR(t.thickness[0], 50 * 0.4, 1e-9);
  EXPECT_LT((t2.thickness - 2 * t.thickness).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((t.weights.rowwise().sum().array() - 1).abs().maxCoeff(), 1e-12);
  EXPECT_EQ(t.fromNearestVoxel, 1);  // the point outside the thin box reads the voxel (10, 3, 3)
  EXPECT_NEAR(t.weights(3, 0), b.W(b.row[g.linearIndex(10, 3, 3)], 0), 1e-12);
  for (Index p = 0; p < 4; ++p) EXPECT_TRUE(t.thickness[p] >= 50 * 0.1 - 1e-9 && t.thickness[p] <= 50 * 0.4 + 1e-9);
  EXPECT_THROW(boneFatThickness(b, P, Eigen::Vector3d(1, 1, 1)), UsageError);
}

}  // namespace
}  // namespace vesalius::fat
