// Mean value coordinates (Ju, Schaefer and Warren 2005): what the paper proves of them, on closed cages.
#include "vesalius/core/error.h"
#include "vesalius/core/mean_value_coordinates.h"

#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace vesalius {
namespace {

// Points inside the unit sphere, some near its surface.
MatrixX3d insidePoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  MatrixX3d P(n, 3);
  for (int i = 0; i < n;) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (p.norm() < 0.97) P.row(i++) = p;
  }
  return P;
}

// Linear precision: values of an affine function at the vertices give that function inside, so a cage
// moved by an affine map moves every inner point by the same map. Over cages of 32 to 2,048 triangles.
TEST(MeanValueCoordinates, ReproduceAffineMapsInsideAnyCage) {
  Eigen::Matrix3d A;
  A << 1.2, 0.1, -0.3, 0.05, 0.8, 0.2, -0.1, 0.3, 1.5;
  const Eigen::Vector3d b(4, -2, 7);
  for (int levels : {1, 2, 3, 4}) {
    const TriMesh cage = test::sphere(levels);
    const MatrixX3d P = insidePoints(200, 7u + unsigned(levels));
    const Eigen::MatrixXd values = (cage.V * A.transpose()).rowwise() + b.transpose();
    const Eigen::MatrixXd got = meanValueInterpolate(cage, values, P);
    const Eigen::MatrixXd want = (P * A.transpose()).rowwise() + b.transpose();
    const double worst = (got - want).rowwise().norm().maxCoeff();
    std::printf("%ld triangles: largest error of the affine map %.2e\n", long(cage.F.rows()), worst);
    EXPECT_LT(worst, 1e-9);
  }
}

// Interpolation: a vertex gets its own value, a point on a triangle its barycentric mix.
TEST(MeanValueCoordinates, InterpolateOnTheCage) {
  const TriMesh cage = test::sphere(2);
  Eigen::MatrixXd values = Eigen::MatrixXd::Random(cage.V.rows(), 2);
  const Eigen::Vector3d bary(0.2, 0.3, 0.5);
  MatrixX3d P(2, 3);
  P.row(0) = cage.V.row(5);
  P.row(1) = bary[0] * cage.V.row(cage.F(9, 0)) + bary[1] * cage.V.row(cage.F(9, 1)) + bary[2] * cage.V.row(cage.F(9, 2));
  const Eigen::MatrixXd got = meanValueInterpolate(cage, values, P);
  EXPECT_LT((got.row(0) - values.row(5)).norm(), 1e-12);
  const Eigen::RowVectorXd want =
      bary[0] * values.row(cage.F(9, 0)) + bary[1] * values.row(cage.F(9, 1)) + bary[2] * values.row(cage.F(9, 2));
  EXPECT_LT((got.row(1) - want).norm(), 1e-9);
}

// Positivity inside a convex cage (the paper's §3.1): the interpolation of values in [0, 1] stays in [0, 1].
TEST(MeanValueCoordinates, StayWithinTheValuesInsideAConvexCage) {
  const TriMesh cage = test::sphere(3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  Eigen::MatrixXd values(cage.V.rows(), 1);
  for (Eigen::Index v = 0; v < values.rows(); ++v) values(v, 0) = u(rng);
  const Eigen::MatrixXd got = meanValueInterpolate(cage, values, insidePoints(300, 11));
  std::printf("interpolated %.4f .. %.4f of values in [0, 1]\n", got.minCoeff(), got.maxCoeff());
  EXPECT_GE(got.minCoeff(), values.minCoeff());
  EXPECT_LE(got.maxCoeff(), values.maxCoeff());
}

TEST(MeanValueCoordinates, BadInput) {
  const TriMesh cage = test::sphere(1);
  EXPECT_THROW(meanValueInterpolate(cage, Eigen::MatrixXd::Zero(3, 1), MatrixX3d::Zero(1, 3)), BadInput);
  EXPECT_THROW(meanValueInterpolate(TriMesh{}, Eigen::MatrixXd::Zero(0, 1), MatrixX3d::Zero(1, 3)), BadInput);
}

}  // namespace
}  // namespace vesalius
