// Shared by the fem tests: box tet meshes, random plastic strains, and central finite differences.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/fem/plastic_strain.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace vesalius::test {

// nx by ny by nz cubes of edge h from the origin, each split into the 6 tets around its main diagonal
// (Freudenthal/Kuhn: conforming across cubes), positively oriented. Vertex (i, j, k) is row
// i + (nx + 1) (j + (ny + 1) k).
inline TetMesh boxTetMesh(int nx, int ny, int nz, double h) {
  TetMesh m;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  m.V.resize((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.V.row(id(i, j, k)) << i * h, j * h, k * h;
  const std::array<std::array<int, 3>, 6> orders{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  std::vector<Eigen::Vector4i> tets;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& order : orders) {
          std::array<int, 3> p{i, j, k};
          Eigen::Vector4i t;
          t[0] = id(p[0], p[1], p[2]);
          for (int c = 0; c < 3; ++c) {
            ++p[order[c]];
            t[c + 1] = id(p[0], p[1], p[2]);
          }
          tets.push_back(t);
        }
  m.T.resize(Eigen::Index(tets.size()), 4);
  for (std::size_t t = 0; t < tets.size(); ++t) m.T.row(Eigen::Index(t)) = tets[t].transpose();
  const Eigen::VectorXd volume = tetVolumes(m.V, m.T);
  for (Eigen::Index t = 0; t < m.T.rows(); ++t)
    if (volume[t] < 0) std::swap(m.T(t, 2), m.T(t, 3));
  return m;
}

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
