// Fixed point constraints compressed to a few rows: on a box's boundary with many points per triangle,
// the compressed energy, its gradient and its Gauss-Newton Hessian equal the constraints' own at random
// positions, with at most 3 rows per involved vertex; with fewer points than vertices the rows are the
// constraints' own.
#include "vesalius/fit/compressed_constraints.h"

#include "test_tets.h"

#include <gtest/gtest.h>

#include <random>

namespace vesalius::fit {
namespace {

// `count` points on the z = 0 face of the box (weight 0 at the fourth corner), random weights and targets.
std::vector<PointConstraint> pointsOnTheBottom(const TetMesh& box, int count, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(0.0, 1.0), target(-20.0, 20.0);
  std::vector<std::array<int, 4>> faces;  // a tet and its three corners on z = 0
  for (int t = 0; t < int(box.T.rows()); ++t) {
    std::array<int, 4> f{t, -1, -1, -1};
    int n = 0;
    for (int k = 0; k < 4; ++k)
      if (box.V(box.T(t, k), 2) == 0.0 && n < 3) f[std::size_t(1 + n++)] = k;
    if (n == 3) faces.push_back(f);
  }
  std::vector<PointConstraint> points;
  for (int i = 0; i < count; ++i) {
    const auto& f = faces[std::size_t(i) % faces.size()];
    PointConstraint c;
    c.tet = f[0];
    for (int k = 0; k < 4; ++k) c.vertices[std::size_t(k)] = box.T(c.tet, k);
    double a = unit(random), b = unit(random);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    c.weights[f[1]] = a;
    c.weights[f[2]] = b;
    c.weights[f[3]] = 1 - a - b;
    c.target = Eigen::Vector3d(target(random), target(random), target(random));
    c.weight = 50.0 + 100.0 * unit(random);
    points.push_back(c);
  }
  return points;
}

TEST(CompressedConstraints, SameEnergyGradientAndHessianWithFewerRows) {
  const TetMesh box = test::boxTets(4, 4, 2, 10.0);
  std::mt19937 random(7);
  const std::vector<PointConstraint> points = pointsOnTheBottom(box, 600, random);
  const CompressedConstraints compressed = compressConstraints(points, box.V.rows());
  EXPECT_LE(compressed.rows.rows(), 3 * 25);  // the 5 × 5 vertices of the bottom face
  EXPECT_LT(compressed.rows.rows(), 3 * Eigen::Index(points.size()));

  const Eigen::SparseMatrix<double> A = constraintRows(points, box.V.rows());
  const Eigen::MatrixXd hessian = Eigen::MatrixXd(A.transpose() * A);
  EXPECT_LE((Eigen::MatrixXd(compressed.rows.transpose() * compressed.rows) - hessian).cwiseAbs().maxCoeff(),
            1e-9 * hessian.cwiseAbs().maxCoeff());
  std::uniform_real_distribution<double> position(-30.0, 30.0);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x(3 * box.V.rows());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = position(random);
    const Eigen::VectorXd r = constraintResiduals(points, x);
    EXPECT_NEAR(compressed.energy(x), 0.5 * r.squaredNorm(), 1e-10 * r.squaredNorm());
    const Eigen::VectorXd gradient = A.transpose() * r;
    EXPECT_LE((compressed.rows.transpose() * compressed.residuals(x) - gradient).norm(), 1e-9 * gradient.norm());
  }
}

TEST(CompressedConstraints, FewPointsKeepTheirOwnRows) {
  const TetMesh box = test::boxTets(2, 2, 2, 10.0);
  std::mt19937 random(3);
  const std::vector<PointConstraint> points = pointsOnTheBottom(box, 2, random);
  const CompressedConstraints compressed = compressConstraints(points, box.V.rows());
  EXPECT_EQ(compressed.rows.rows(), 6);
  EXPECT_EQ(compressed.offset, 0.0);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(3 * box.V.rows(), -5.0, 7.0);
  EXPECT_NEAR(compressed.energy(x), 0.5 * constraintResiduals(points, x).squaredNorm(), 1e-9);
  EXPECT_EQ(compressConstraints({}, box.V.rows()).rows.rows(), 0);
}

}  // namespace
}  // namespace vesalius::fit
