#include "vesalius/core/error.h"
#include "vesalius/core/principal_axes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace vesalius {
namespace {

// A box of points 60 × 20 × 8 mm (variances 300, 33.3 and 5.3 mm² for a uniform grid), turned and moved:
// the axes come back as the turned x, y, z up to sign, the variances decreasing, the centroid the move.
TEST(PrincipalAxes, ABoxGivesItsTurnedEdgesLongestFirst) {
  MatrixX3d P(11 * 11 * 11, 3);
  Eigen::Index r = 0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j)
      for (int k = 0; k <= 10; ++k) P.row(r++) << 6.0 * i - 30, 2.0 * j - 10, 0.8 * k - 4;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(12, -40, 250);
  const MatrixX3d Q = (P * R.transpose()).rowwise() + t.transpose();
  const PrincipalAxes a = principalAxes(Q);
  EXPECT_LT((a.centroid - t).norm(), 1e-9);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(std::abs(a.axes.col(c).dot(R.col(c))), 1.0, 1e-12) << c;
  EXPECT_NEAR(a.axes.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(a.variances[0], 36.0 * 10.0, 1e-9);  // a uniform grid of 11 steps: variance 10 steps²
  EXPECT_NEAR(a.variances[1], 4.0 * 10.0, 1e-9);
  EXPECT_NEAR(a.variances[2], 0.64 * 10.0, 1e-9);
}

TEST(PrincipalAxes, NoPointsIsBadInput) { EXPECT_THROW(principalAxes(MatrixX3d(0, 3)), BadInput); }

}  // namespace
}  // namespace vesalius
