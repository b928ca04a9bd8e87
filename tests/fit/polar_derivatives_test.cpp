#include "vesalius/fit/polar_derivatives.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace vesalius::fit {
namespace {

Eigen::Matrix3d unit(int i) {
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(i % 3, i / 3) = 1.0;
  return E;
}

Eigen::Matrix3d randomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng)).normalized().toRotationMatrix();
}

// Deformation gradients with det > 0: generic, near-rotations and strongly anisotropic stretches.
std::vector<Eigen::Matrix3d> testMatrices() {
  std::mt19937 rng(7);
  std::vector<Eigen::Matrix3d> Fs;
  for (int n = 0; n < 4; ++n) {
    Eigen::Matrix3d F = Eigen::Matrix3d::Random() + Eigen::Matrix3d::Identity();
    if (F.determinant() < 0) F.col(0) *= -1.0;
    Fs.push_back(F);
  }
  for (int n = 0; n < 2; ++n) Fs.push_back(randomRotation(rng) + 1e-7 * Eigen::Matrix3d::Random());
  Fs.push_back(randomRotation(rng));
  Fs.push_back(randomRotation(rng) * Eigen::Vector3d(20.0, 1.0, 0.05).asDiagonal() * randomRotation(rng));
  Fs.push_back(randomRotation(rng) * Eigen::Vector3d(3.0, 3.0, 0.2).asDiagonal() * randomRotation(rng));
  return Fs;
}

// Step relative to the smallest singular value, which sets the scale on which R varies.
double stepFor(const Eigen::Matrix3d& F, double relative) {
  return relative * Eigen::JacobiSVD<Eigen::Matrix3d>(F).singularValues().minCoeff();
}

TEST(PolarDerivatives, RotationTimesStretchIsF) {
  for (const Eigen::Matrix3d& F : testMatrices()) {
    const PolarDerivatives polar(F);
    const Eigen::Matrix3d& R = polar.rotation();
    const Eigen::Matrix3d& S = polar.stretch();
    EXPECT_LT((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-13);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-13);
    EXPECT_LT((R * S - F).norm() / F.norm(), 1e-13);
    EXPECT_LT((S - S.transpose()).norm(), 1e-12 * S.norm());
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues().minCoeff(), 0.0);
    EXPECT_EQ(polarRotation(F), R);
  }
}

TEST(PolarDerivatives, FirstDerivativesMatchCentralDifferences) {
  double worst = 0.0;
  for (const Eigen::Matrix3d& F : testMatrices()) {
    const Matrix9d& J = PolarDerivatives(F).first();
    const double h = stepFor(F, 1e-5);
    Matrix9d fd;
    for (int i = 0; i < 9; ++i) {
      const Eigen::Matrix3d d = (polarRotation(F + h * unit(i)) - polarRotation(F - h * unit(i))) / (2 * h);
      fd.col(i) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(d.data());
    }
    const double error = (fd - J).norm() / J.norm();
    EXPECT_LT(error, 1e-6) << F;
    worst = std::max(worst, error);
  }
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
}

TEST(PolarDerivatives, SecondDerivativesMatchCentralDifferencesOfFirst) {
  double worst = 0.0;
  for (const Eigen::Matrix3d& F : testMatrices()) {
    const auto H = PolarDerivatives(F).second();
    const double h = stepFor(F, 1e-4);
    double error = 0.0, norm = 0.0;
    for (int j = 0; j < 9; ++j) {
      const Matrix9d d = (PolarDerivatives(F + h * unit(j)).first() - PolarDerivatives(F - h * unit(j)).first()) / (2 * h);
      for (int k = 0; k < 9; ++k) {
        error += (d.row(k).transpose() - H[std::size_t(k)].col(j)).squaredNorm();
        norm += H[std::size_t(k)].col(j).squaredNorm();
      }
    }
    EXPECT_LT(std::sqrt(error / norm), 1e-6) << F;
    worst = std::max(worst, std::sqrt(error / norm));
    for (const Matrix9d& Hk : H) EXPECT_LT((Hk - Hk.transpose()).norm(), 1e-12 * (1.0 + Hk.norm()));
  }
  RecordProperty("worst_relative_error", testing::PrintToString(worst));
}

TEST(PolarDerivatives, RejectsInversionsAndSingularMatrices) {
  const Eigen::Matrix3d mirror = Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal();
  const Eigen::Matrix3d flat = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  for (const Eigen::Matrix3d& F : {mirror, flat, nan}) {
    EXPECT_THROW(polarRotation(F), NumericalFailure);
    EXPECT_THROW(PolarDerivatives{F}, NumericalFailure);
  }
}

}  // namespace
}  // namespace vesalius::fit
