// Cavities sealed at an opening width (sealed_cavities.h): a ball of radius 30 mm holding a void of radius
// 10 mm that a channel 6 mm wide joins to the outside, with a wide dent (24 mm across) in its surface. The
// void is a cavity when openings of 10 mm are sealed and not when only openings of 4 mm are; the dent is
// never one. Signed distances are those of the shapes (CSG), clamped to a 6 mm band as the CLI's are.
#include "vesalius/meshing/sealed_cavities.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace vesalius::meshing {
namespace {

constexpr double kVoidRadius = 10.0, kChannelRadius = 3.0, kBand = 6.0;

double ballWithPockets(const Eigen::Vector3d& p) {
  const double ball = p.norm() - 30.0;
  const double voidSphere = p.norm() - kVoidRadius;
  const double channel = std::max(std::hypot(p.x(), p.y()) - kChannelRadius, -p.z());  // up from the centre
  const double dent = (p - Eigen::Vector3d(0, 0, -30)).norm() - 12.0;
  return std::max(ball, -std::min({voidSphere, channel, dent}));
}

Grid<float> sampled(const Eigen::Vector3d& spacing) {
  GridGeometry g;
  g.spacing = spacing;
  g.size = (Eigen::Vector3d::Constant(80.0).cwiseQuotient(spacing)).cast<int>();
  g.origin = -0.5 * (g.size.cast<double>() - Eigen::Vector3d::Ones()).cwiseProduct(spacing);
  Grid<float> d(g);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        d.at(i, j, k) = float(std::clamp(ballWithPockets(g.indexToWorld(Eigen::Vector3d(i, j, k))), -kBand, kBand));
  return d;
}

struct Found {
  double volumeMm3 = 0, lowestZ = 1e9;
  long insideVoxels = 0;
};

Found cavitiesOf(const Grid<float>& d, double openingMm) {
  const Grid<std::uint8_t> cavities = sealedCavities(d, openingMm);
  Found f;
  const GridGeometry& g = d.geometry;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        if (!cavities.at(i, j, k)) continue;
        f.volumeMm3 += g.spacing.prod();
        f.lowestZ = std::min(f.lowestZ, g.indexToWorld(Eigen::Vector3d(i, j, k)).z());
        f.insideVoxels += d.at(i, j, k) <= 0;
      }
  return f;
}

TEST(SealedCavities, TheVoidBehindANarrowChannelIsSealed) {
  const double voidVolume = 4.0 / 3.0 * M_PI * std::pow(kVoidRadius, 3);  // 4,189 mm^3
  for (const Eigen::Vector3d& spacing : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.8, 1.0, 1.5)}) {
    const Found sealed = cavitiesOf(sampled(spacing), 10.0);
    EXPECT_NEAR(sealed.volumeMm3, voidVolume, 0.08 * voidVolume) << spacing.transpose();
    EXPECT_GT(sealed.lowestZ, -kVoidRadius - 1.0) << "the dent is open";
    EXPECT_EQ(sealed.insideVoxels, 0);
  }
}

TEST(SealedCavities, AChannelWiderThanTheOpeningStaysOpen) {
  EXPECT_EQ(cavitiesOf(sampled(Eigen::Vector3d(1, 1, 1)), 4.0).volumeMm3, 0.0);
}

TEST(SealedCavities, RefusesAnOpeningThatIsNotPositive) {
  const Grid<float> d = sampled(Eigen::Vector3d(2, 2, 2));
  EXPECT_THROW(sealedCavities(d, 0.0), UsageError);
  EXPECT_THROW(sealedCavities(d, std::nan("")), UsageError);
}

}  // namespace
}  // namespace vesalius::meshing
