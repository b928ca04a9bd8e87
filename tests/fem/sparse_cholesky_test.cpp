#include "vesalius/fem/sparse_cholesky.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <vector>

namespace vesalius {
namespace {

// 1D Laplacian with a grounded end: SPD, tridiagonal.
Eigen::SparseMatrix<double> pathLaplacian(int n, double ground) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, (i == 0 ? ground : 0.0) + (i > 0) + (i + 1 < n));
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -1.0);
      t.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

TEST(SparseCholesky, SolvesManyRightHandSidesAndRefactorsWithSamePattern) {
  const int n = 200;
  SparseCholesky chol;
  for (double ground : {1.0, 3.0}) {
    const auto A = pathLaplacian(n, ground);
    chol.factor(A);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 7);
    const Eigen::MatrixXd X = chol.solve(B);
    EXPECT_LT((A * X - B).norm() / B.norm(), 1e-10) << "ground " << ground;
  }
  EXPECT_EQ(chol.size(), n);
}

TEST(SparseCholesky, RefusesIndefiniteAndEmptyMatrices) {
  SparseCholesky chol;
  EXPECT_THROW(chol.factor(pathLaplacian(10, 0.0) * -1.0), NumericalFailure);
  EXPECT_THROW(chol.factor(Eigen::SparseMatrix<double>()), NumericalFailure);
  EXPECT_THROW(chol.solve(Eigen::VectorXd(Eigen::VectorXd::Ones(3))), NumericalFailure);
}

}  // namespace
}  // namespace vesalius
