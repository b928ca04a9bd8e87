#include "vesalius/fit/woodbury.h"

#include "vesalius/core/error.h"
#include "test_tets.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <string>

namespace vesalius::fit {
namespace {

struct Problem {
  Eigen::SparseMatrix<double> Lsc;
  Eigen::MatrixXd Z;  // 30 random constraint rows
  Eigen::MatrixXd H;  // dense L² + ZᵀZ
};

Problem smallProblem() {
  Problem p;
  p.Lsc = tetAdjacencyLaplacian(test::boxTets(3, 3, 3).T);
  const Eigen::Index n = 6 * p.Lsc.rows();
  p.Z = Eigen::MatrixXd::Random(30, n);
  p.H = p.Z.transpose() * p.Z;
  for (Eigen::Index j = 0; j < n; ++j)
    p.H.col(j) += applyPlasticLaplacian(p.Lsc, applyPlasticLaplacian(p.Lsc, Eigen::VectorXd::Unit(n, j)));
  return p;
}

TEST(WoodburySolver, MatchesDenseDirectSolve) {
  const Problem p = smallProblem();
  const SmoothnessBaseSolver base(p.Lsc);
  const WoodburySolver woodbury(base, ConstraintJacobian(p.Z));
  const Eigen::MatrixXd h = Eigen::MatrixXd::Random(p.H.rows(), 3);
  const Eigen::MatrixXd expected = p.H.llt().solve(h);
  const Eigen::MatrixXd y = woodbury.solve(h);
  const double error = (y - expected).norm() / expected.norm();
  EXPECT_LT(error, 1e-8);
  EXPECT_LT((woodbury.solve(Eigen::MatrixXd(h.col(1))) - y.col(1)).norm(), 1e-12 * y.col(1).norm());
  RecordProperty("relative_error", testing::PrintToString(error));
}

TEST(WoodburySolver, DampedSolveMatchesDenseDirectSolve) {
  // H + μ (L² + Σψψᵀ) for a few μ, switching μ back and forth on one solver.
  const Problem p = smallProblem();
  const SmoothnessBaseSolver base(p.Lsc);
  WoodburySolver woodbury(base, ConstraintJacobian(p.Z));
  const Eigen::MatrixXd psi = plasticLaplacianNullspace(p.Lsc.rows());
  const Eigen::MatrixXd D = p.H - p.Z.transpose() * p.Z + psi * psi.transpose();
  const Eigen::MatrixXd h = Eigen::MatrixXd::Random(p.H.rows(), 2);
  for (double mu : {0.5, 3.0, 1e-4, 0.0}) {
    woodbury.setDamping(mu);
    const Eigen::MatrixXd expected = (p.H + mu * D).llt().solve(h);
    EXPECT_LT((woodbury.solve(h) - expected).norm() / expected.norm(), 1e-8) << "mu " << mu;
  }
}

TEST(WoodburySolver, AgreesWithConjugateGradients) {
  const Problem p = smallProblem();
  const SmoothnessBaseSolver base(p.Lsc);
  const Eigen::VectorXd h = Eigen::VectorXd::Random(p.H.rows());
  const Eigen::VectorXd y = WoodburySolver(base, ConstraintJacobian(p.Z)).solve(Eigen::MatrixXd(h));
  const ConjugateGradientResult cg = solveConjugateGradient(p.Lsc, ConstraintJacobian(p.Z), h, 1e-13, 100000);
  EXPECT_LT(cg.relativeResidual, 1e-12);
  EXPECT_GT(cg.iterations, 0);
  const double error = (cg.y - y).norm() / y.norm();
  EXPECT_LT(error, 1e-8);
  RecordProperty("relative_difference", testing::PrintToString(error));
  RecordProperty("cg_iterations", cg.iterations);
  const ConjugateGradientResult capped = solveConjugateGradient(p.Lsc, ConstraintJacobian(p.Z), h, 1e-13, 5);
  EXPECT_EQ(capped.iterations, 5);
  EXPECT_GT(capped.relativeResidual, 1e-6);
}

TEST(WoodburySolver, RejectsSingularHAndMismatchedSizes) {
  const Problem p = smallProblem();
  const SmoothnessBaseSolver base(p.Lsc);
  // Without constraints H = L² is singular.
  EXPECT_THROW(WoodburySolver(base, ConstraintJacobian(Eigen::MatrixXd(0, p.Z.cols()))), NumericalFailure);
  EXPECT_THROW(WoodburySolver(base, ConstraintJacobian(Eigen::MatrixXd(p.Z.leftCols(12)))), BadInput);
  EXPECT_THROW(solveConjugateGradient(p.Lsc, ConstraintJacobian(p.Z), Eigen::VectorXd::Ones(5), 1e-8, 10), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
