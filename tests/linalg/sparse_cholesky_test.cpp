#include "vesalius/linalg/sparse_cholesky.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <iostream>
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

// The 7-point Laplacian of an n³ grid with one corner grounded.
Eigen::SparseMatrix<double> gridLaplacian(int n) {
  std::vector<Eigen::Triplet<double>> t;
  const auto index = [n](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = index(i, j, k);
        if (a == 0) t.emplace_back(a, a, 1.0);
        for (const auto& [di, dj, dk] : {std::array<int, 3>{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) {
          if (i + di >= n || j + dj >= n || k + dk >= n) continue;
          const int b = index(i + di, j + dj, k + dk);
          t.insert(t.end(), {{a, b, -1.0}, {b, a, -1.0}, {a, a, 1.0}, {b, b, 1.0}});
        }
      }
  Eigen::SparseMatrix<double> A(n * n * n, n * n * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// Nested dissection solves the same system with less fill than the default on a 3D mesh graph.
TEST(SparseCholesky, NestedDissectionSolvesWithLessFill) {
  const Eigen::SparseMatrix<double> A = gridLaplacian(20);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 5);
  SparseCholesky automatic, dissected(FillReducingOrdering::nestedDissection);
  EXPECT_EQ(dissected.factorEntries(), 0.0);
  automatic.factor(A);
  dissected.factor(A);
  const Eigen::MatrixXd X = dissected.solve(B);
  EXPECT_LT((A * X - B).norm() / B.norm(), 1e-10);
  EXPECT_LT((X - automatic.solve(B)).norm() / X.norm(), 1e-9);
  std::cout << "fill of a 20³ grid Laplacian: automatic " << automatic.factorEntries() << ", nested dissection "
            << dissected.factorEntries() << "\n";
  EXPECT_LT(dissected.factorEntries(), 0.9 * automatic.factorEntries());
}

// A row-major block built in the factor's row order and solved in place is the solution in that order,
// on more columns than one parallel block (256) holds: two blocks that share each row.
TEST(SparseCholesky, SolvesRowMajorBlocksInTheFactorsRowOrder) {
  const Eigen::SparseMatrix<double> A = gridLaplacian(12);
  SparseCholesky chol(FillReducingOrdering::nestedDissection);
  chol.factor(A);
  const Eigen::VectorXi order = chol.permutation();
  ASSERT_EQ(order.size(), A.rows());
  EXPECT_NE(order, Eigen::VectorXi::LinSpaced(A.rows(), 0, int(A.rows()) - 1));  // really reordered
  Eigen::VectorXi sorted = order;
  std::sort(sorted.data(), sorted.data() + sorted.size());
  EXPECT_EQ(sorted, Eigen::VectorXi::LinSpaced(A.rows(), 0, int(A.rows()) - 1));  // a permutation
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 300);
  RowMajorMatrixXd X = B(order, Eigen::all);
  chol.solvePermutedInPlace(X);
  Eigen::MatrixXd solution(A.rows(), B.cols());
  solution(order, Eigen::all) = X;
  EXPECT_LT((A * solution - B).norm() / B.norm(), 1e-10);
  EXPECT_LT((solution - chol.solve(B)).norm() / solution.norm(), 1e-13);
  RowMajorMatrixXd wrongSize = RowMajorMatrixXd::Ones(A.rows() - 1, 2);
  EXPECT_THROW(chol.solvePermutedInPlace(wrongSize), NumericalFailure);
}

TEST(SparseCholesky, RefusesIndefiniteAndEmptyMatrices) {
  SparseCholesky chol;
  EXPECT_THROW(chol.factor(pathLaplacian(10, 0.0) * -1.0), NumericalFailure);
  EXPECT_THROW(chol.factor(Eigen::SparseMatrix<double>()), NumericalFailure);
  EXPECT_THROW(chol.solve(Eigen::VectorXd(Eigen::VectorXd::Ones(3))), NumericalFailure);
  EXPECT_THROW(chol.permutation(), NumericalFailure);
  RowMajorMatrixXd X = RowMajorMatrixXd::Ones(3, 2);
  EXPECT_THROW(chol.solvePermutedInPlace(X), NumericalFailure);
}

}  // namespace
}  // namespace vesalius
