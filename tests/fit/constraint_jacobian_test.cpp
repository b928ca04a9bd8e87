#include "vesalius/fit/constraint_jacobian.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <random>
#include <tuple>
#include <vector>

namespace vesalius::fit {
namespace {

// Z = −Wᵀ G for a random dense Wᵀ (#C by n) and a sparse G (n by p) with a few entries per column, as the
// plastic force Jacobian has; every use must agree with the matrix formed.
struct Factors {
  Eigen::MatrixXd Wt;
  Eigen::SparseMatrix<double> G;
  Eigen::MatrixXd Z;
};

Factors randomFactors(Eigen::Index C, Eigen::Index n, Eigen::Index p) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> row(0, int(n) - 1);
  std::normal_distribution<double> value;
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index j = 0; j < p; ++j)
    for (int k = 0; k < 12; ++k) entries.emplace_back(row(random), int(j), value(random));
  Factors f;
  f.G.resize(n, p);
  f.G.setFromTriplets(entries.begin(), entries.end());
  f.Wt = Eigen::MatrixXd::Random(C, n);
  f.Z = -(f.Wt * f.G);
  return f;
}

TEST(ConstraintJacobian, FactoredProductsMatchTheFormedMatrix) {
  const std::tuple<int, int, int> sizes[] = {{30, 90, 600}, {7, 9000, 10000}, {1, 12, 6}};
  for (const auto& [C, n, p] : sizes) {
    const Factors f = randomFactors(C, n, p);
    const ConstraintJacobian Z(f.Wt, f.G);
    ASSERT_EQ(Z.rows(), C);
    ASSERT_EQ(Z.cols(), p);
    const Eigen::MatrixXd y = Eigen::MatrixXd::Random(p, 3), x = Eigen::MatrixXd::Random(C, 2);
    const double scale = f.Z.norm();
    EXPECT_LT((Z * y - f.Z * y).norm(), 1e-13 * scale * y.norm()) << C << " by " << p;
    EXPECT_LT((Z.transposeTimes(x) - f.Z.transpose() * x).norm(), 1e-13 * scale * x.norm()) << C << " by " << p;
    Eigen::VectorXd column(C);
    for (const Eigen::Index j : {Eigen::Index(0), Eigen::Index(p / 2), Eigen::Index(p - 1)}) {
      Z.column(j, column);
      EXPECT_LT((column - f.Z.col(j)).norm(), 1e-13 * scale) << "column " << j;
    }
    EXPECT_NEAR(Z.squaredNorm(), f.Z.squaredNorm(), 1e-12 * f.Z.squaredNorm());
    // The formed-matrix constructor gives the same products.
    const ConstraintJacobian dense(f.Z);
    EXPECT_LT((dense * y - f.Z * y).norm(), 1e-13 * scale * y.norm());
    EXPECT_NEAR(dense.squaredNorm(), f.Z.squaredNorm(), 1e-12 * f.Z.squaredNorm());
  }
}

TEST(ConstraintJacobian, RejectsMismatchedSizes) {
  const Factors f = randomFactors(5, 20, 30);
  EXPECT_THROW(ConstraintJacobian(Eigen::MatrixXd(f.Wt.leftCols(19)), f.G), BadInput);
  const ConstraintJacobian Z(f.Wt, f.G);
  EXPECT_THROW(Z * Eigen::MatrixXd::Ones(29, 1), BadInput);
  EXPECT_THROW(Z.transposeTimes(Eigen::MatrixXd::Ones(4, 1)), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
