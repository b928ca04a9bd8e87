// Bones bent inside their skin (bones_warped_into_skin.h), on a sphere of radius 100 mm as the skin.
#include "vesalius/transfer/bones_warped_into_skin.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>

namespace vesalius::transfer {
namespace {

constexpr double kRadius = 100.0;

SkinDistances sphereDistances(const MatrixX3d& P) { return {P.rowwise().norm().array() - kRadius, P.rowwise().normalized()}; }

// A bar along +z from z0, 100 mm long and 10 mm thick, vertices every 2 mm along it.
MatrixX3d bar(double z0) {
  MatrixX3d V(51 * 8, 3);
  for (int i = 0; i <= 50; ++i)
    for (int k = 0; k < 8; ++k) {
      const double angle = 2 * M_PI * k / 8;
      V.row(i * 8 + k) << 5 * std::cos(angle), 5 * std::sin(angle), z0 + 2.0 * i;
    }
  return V;
}

// The bar's tip pokes 5 mm out: the warp brings every vertex the margin inside, bends the tip's last
// radius of bar and leaves the rest where it was.
TEST(BonesWarpedIntoSkin, ATipPokingOutIsBentInAndTheRestStays) {
  const MatrixX3d V = bar(5.0);  // the tip's ring at z = 105, 0.1 mm further out at its rim
  const InsideSkinWarp warp = warpIntoSkin(V, sphereDistances);
  const MatrixX3d W = warp.apply(V);
  EXPECT_GT(warp.outsideBefore, 0);
  EXPECT_EQ(warp.outsideAfter, 0);
  const double deepest = sphereDistances(W).distance.maxCoeff();
  std::printf("outside before %ld, deepest after %.2f mm, largest move %.2f mm in %zu rounds\n", warp.outsideBefore,
              deepest, warp.largestMoveMm, warp.centres.size());
  EXPECT_LT(deepest, 0.0);
  EXPECT_GT(deepest, -1.6);  // the margin is 1.5 mm; the ridge undershoots, the rounds stop once inside
  EXPECT_NEAR(warp.largestMoveMm, (W - V).rowwise().norm().maxCoeff(), 1e-12);
  EXPECT_LT(warp.largestMoveMm, 7.0);  // 5.1 out + 1.5 margin
  // Beyond the kernel's 60 mm from every vertex that was outside (z ≥ 95) nothing moves.
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (V(v, 2) < 30.0) {
      EXPECT_EQ((W.row(v) - V.row(v)).norm(), 0.0) << v;
    }
  // Bent, not crushed: rings 2 mm apart along the bar move by nearly the same amount (measured: at most
  // 0.52 mm, a strain of 26 %, where the push is along the bar; with R = 40 mm 0.79 mm).
  double steepest = 0;
  for (int i = 0; i < 50; ++i)
    steepest = std::max(steepest, (W.row(i * 8) - V.row(i * 8) - (W.row(i * 8 + 8) - V.row(i * 8 + 8))).norm());
  std::printf("steepest change between rings 2 mm apart %.3f mm\n", steepest);
  EXPECT_LT(steepest, 0.6);
}

// Depths wanted per vertex: a vertex of the tip ring left alone (+∞) is not counted; the others wanted
// 0.5 mm deep end inside, the shallowest of them about that deep (with the default margin, 1.5 mm).
TEST(BonesWarpedIntoSkin, WantedDepthsPerVertex) {
  const MatrixX3d V = bar(5.0);
  const Eigen::Index alone = 50 * 8;  // a vertex of the tip ring
  Eigen::VectorXd wanted = Eigen::VectorXd::Constant(V.rows(), -0.5);
  wanted[alone] = std::numeric_limits<double>::infinity();
  const InsideSkinWarp warp = warpIntoSkin(V, sphereDistances, wanted);
  Eigen::VectorXd d = sphereDistances(warp.apply(V)).distance;
  EXPECT_EQ(warp.outsideBefore, 23);  // 24 outside, one of them left alone
  EXPECT_EQ(warp.outsideAfter, 0);
  d[alone] = -std::numeric_limits<double>::infinity();
  std::printf("shallowest %.2f mm deep\n", -d.maxCoeff());
  EXPECT_LE(d.maxCoeff(), 0.0);
  EXPECT_GT(d.maxCoeff(), -0.6);
  EXPECT_THROW(warpIntoSkin(V, sphereDistances, Eigen::VectorXd::Constant(V.rows(), 0.5)), UsageError);
  EXPECT_THROW(warpIntoSkin(V, sphereDistances, Eigen::VectorXd::Constant(3, -1.0)), UsageError);
}

// Two toes of skin (cylinders along y of radius 5 mm, 12 mm apart, a cleft of 2 mm between) round two
// toes of bone side by side (radius 3 mm, 6 mm apart) that fill the cleft: each bone toe must move out its
// own way. A bend as long as a limb does not part them; the stage at a toe's reach does.
SkinDistances twoToes(const MatrixX3d& P) {
  SkinDistances d{Eigen::VectorXd(P.rows()), MatrixX3d(P.rows(), 3)};
  for (Eigen::Index r = 0; r < P.rows(); ++r) {
    const Eigen::Vector3d axis(P(r, 0) < 0 ? -6.0 : 6.0, P(r, 1), 0.0), away = P.row(r).transpose() - axis;
    d.distance[r] = away.norm() - 5.0;
    d.outward.row(r) = away.normalized().transpose();
  }
  return d;
}

TEST(BonesWarpedIntoSkin, TwoToesArePartedByTheShorterReach) {
  MatrixX3d V(2 * 21 * 8, 3);
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i <= 20; ++i)
      for (int k = 0; k < 8; ++k) {
        const double angle = 2 * M_PI * k / 8;
        V.row((side * 21 + i) * 8 + k) << (side ? 3.0 : -3.0) + 3 * std::cos(angle), 2.0 * i, 3 * std::sin(angle);
      }
  InsideSkinWarpOptions coarse;
  coarse.radiiMm = {60.0};
  const InsideSkinWarp limb = warpIntoSkin(V, twoToes, coarse), toe = warpIntoSkin(V, twoToes);
  const Eigen::VectorXd d = twoToes(toe.apply(V)).distance;
  std::printf("outside before %ld, after the limb's reach %ld, after the toe's %ld (largest move %.2f mm, shallowest "
              "%.2f mm)\n", toe.outsideBefore, limb.outsideAfter, toe.outsideAfter, toe.largestMoveMm, -d.maxCoeff());
  EXPECT_EQ(toe.outsideBefore, 2 * 21 * 3);  // the three inner vertices of every ring
  EXPECT_GT(limb.outsideAfter, 0);           // measured 8
  EXPECT_EQ(toe.outsideAfter, 0);
  EXPECT_LE(d.maxCoeff(), 0.0);
  EXPECT_LT(toe.largestMoveMm, 6.0);  // from the cleft's middle to the margin inside a toe: 2.5 mm at least
}

// A lone vertex far out, with rounds too few to bring it in: each round moves it half its way to the
// margin (λ = 1, φ(0) = 1), d → (d − m) / 2, and rounds that leave it nearer are kept though the count of
// vertices outside stays 1.
TEST(BonesWarpedIntoSkin, RoundsThatBringTheLastVertexNearerAreKept) {
  const MatrixX3d V = Eigen::RowVector3d(0, 0, kRadius + 20.0);
  InsideSkinWarpOptions o;
  o.radiiMm = {60.0};
  o.rounds = 2;
  const InsideSkinWarp warp = warpIntoSkin(V, sphereDistances, o);
  const double after = sphereDistances(warp.apply(V)).distance[0];
  const double expected = ((20.0 - o.marginMm) / 2 - o.marginMm) / 2;
  std::printf("20 mm out, after two rounds %.4f mm out (expected %.4f), %zu rounds kept\n", after, expected,
              warp.centres.size());
  EXPECT_EQ(warp.outsideAfter, 1);
  EXPECT_EQ(warp.centres.size(), 2u);
  EXPECT_NEAR(after, expected, 1e-9);
  EXPECT_NEAR(warp.largestMoveMm, 20.0 - expected, 1e-9);
}

TEST(BonesWarpedIntoSkin, ABoneInsideIsNotMoved) {
  const MatrixX3d V = bar(-50.0);
  const InsideSkinWarp warp = warpIntoSkin(V, sphereDistances);
  EXPECT_EQ(warp.outsideBefore, 0);
  EXPECT_TRUE(warp.centres.empty());
  EXPECT_EQ((warp.apply(V) - V).norm(), 0.0);
}

TEST(BonesWarpedIntoSkin, BadInput) {
  EXPECT_THROW(warpIntoSkin(MatrixX3d(0, 3), sphereDistances), UsageError);
  InsideSkinWarpOptions o;
  o.radiiMm = {60.0, 0.0};
  EXPECT_THROW(warpIntoSkin(bar(0.0), sphereDistances, o), UsageError);
  o = {};
  o.passes = 0;
  EXPECT_THROW(warpIntoSkin(bar(0.0), sphereDistances, o), UsageError);
}

}  // namespace
}  // namespace vesalius::transfer
