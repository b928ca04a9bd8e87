// Shared by the fem tests: random plastic strains and central finite differences (box tet meshes come from
// test_tets.h).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/fem/plastic_strain.h"

#include "test_tets.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace vesalius::test {

// Symmetric positive definite Fp near `centre` (eigenvalues stay well above zero for spread < 0.3).
inline Vector6d randomPlasticStrain(std::mt19937& rng, const Eigen::Matrix3d& centre, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  Eigen::Matrix3d E;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) E(i, j) = u(rng);
  return plasticStrainParameters(centre + 0.5 * (E + E.transpose()));
}

// Central differences of f: R^n -> R^m (f returns an Eigen vector) at x: m by n.
template <class F>
Eigen::MatrixXd centralDifferences(F f, const Eigen::VectorXd& x, double step) {
  Eigen::MatrixXd J;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x, minus = x;
    plus[i] += step;
    minus[i] -= step;
    const Eigen::VectorXd column = (f(plus) - f(minus)) / (2 * step);
    if (i == 0) J.resize(column.size(), x.size());
    J.col(i) = column;
  }
  return J;
}

inline std::string scientific(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2e", v);
  return text;
}

// ||actual - expected|| / ||expected|| below bound; the measured value goes into the test report
// (--gtest_output) under `name`.
inline void expectRelativeError(const std::string& name, const Eigen::MatrixXd& actual,
                                const Eigen::MatrixXd& expected, double bound) {
  ASSERT_EQ(actual.rows(), expected.rows()) << name;
  ASSERT_EQ(actual.cols(), expected.cols()) << name;
  const double error = (actual - expected).norm() / expected.norm();
  ::testing::Test::RecordProperty(name, scientific(error));
  EXPECT_LT(error, bound) << name;
}

}  // namespace vesalius::test
