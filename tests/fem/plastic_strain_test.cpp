#include "vesalius/fem/plastic_strain.h"

#include "fem_test_support.h"

#include <Eigen/Eigenvalues>

namespace vesalius {
namespace {

TEST(PlasticStrain, MatrixFollowsEquation2AndRoundTrips) {
  Vector6d s;
  s << 1, 2, 3, 4, 5, 6;
  Eigen::Matrix3d expected;
  expected << 1, 2, 3, 2, 4, 5, 3, 5, 6;
  EXPECT_EQ(plasticStrainMatrix(s), expected);
  EXPECT_EQ(plasticStrainParameters(expected), s);
  EXPECT_EQ(plasticStrainMatrix(identityPlasticStrain()), Eigen::Matrix3d::Identity());
  const Eigen::Matrix<double, 9, 6> Y = plasticStrainJacobian();
  const Eigen::Matrix<double, 9, 1> vecFp = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(expected.data());
  EXPECT_EQ(vecFp, Y * s);
}

TEST(PlasticStrain, ClampRaisesSmallEigenvaluesOnly) {
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -1, 2).normalized()).toRotationMatrix();
  const Vector6d s = plasticStrainParameters(Q * Eigen::Vector3d(-0.5, 0.005, 2.0).asDiagonal() * Q.transpose());
  const Vector6d clamped = clampPlasticStrain(s, 0.01);
  const Eigen::Matrix3d expected = Q * Eigen::Vector3d(0.01, 0.01, 2.0).asDiagonal() * Q.transpose();
  EXPECT_LT((plasticStrainMatrix(clamped) - expected).norm(), 1e-12);
  const Vector6d fine = plasticStrainParameters(Q * Eigen::Vector3d(0.5, 1, 2).asDiagonal() * Q.transpose());
  EXPECT_EQ(clampPlasticStrain(fine, 0.01), fine);
}

}  // namespace
}  // namespace vesalius
