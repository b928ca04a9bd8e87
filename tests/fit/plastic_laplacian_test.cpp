#include "vesalius/fit/plastic_laplacian.h"

#include "vesalius/core/error.h"
#include "test_tets.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <string>

namespace vesalius::fit {
namespace {

MatrixX4i cubeGridTets(int n) { return test::boxTets(n, n, n).T; }

// L as a dense 6#T by 6#T matrix, one column per unit vector.
Eigen::MatrixXd densePlasticLaplacian(const Eigen::SparseMatrix<double>& Lsc) {
  const Eigen::Index n = 6 * Lsc.rows();
  Eigen::MatrixXd L(n, n);
  for (Eigen::Index j = 0; j < n; ++j) L.col(j) = applyPlasticLaplacian(Lsc, Eigen::VectorXd::Unit(n, j));
  return L;
}

TEST(PlasticLaplacian, AdjacencyLaplacianOfACubeGrid) {
  // One cube: the 6 Kuhn tets form a cycle through shared faces.
  const Eigen::MatrixXd cycle = tetAdjacencyLaplacian(cubeGridTets(1));
  EXPECT_EQ(cycle.diagonal(), Eigen::VectorXd::Constant(6, 2.0));
  const int n = 3;
  const Eigen::SparseMatrix<double> Lsc = tetAdjacencyLaplacian(cubeGridTets(n));
  const Eigen::MatrixXd L = Lsc;
  EXPECT_EQ(L, L.transpose());
  EXPECT_EQ(L.rowwise().sum(), Eigen::VectorXd::Zero(L.rows()));
  EXPECT_LE(L.diagonal().maxCoeff(), 4.0);
  // Every face not on the 12 n² boundary triangles is shared by two tets.
  EXPECT_EQ(L.trace(), 4.0 * L.rows() - 12.0 * n * n);
}

TEST(PlasticLaplacian, NullspaceIsExactlySixDimensional) {
  const Eigen::SparseMatrix<double> Lsc = tetAdjacencyLaplacian(cubeGridTets(3));
  const Eigen::MatrixXd L = densePlasticLaplacian(Lsc);
  const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(L * L).eigenvalues();
  EXPECT_LT(eigenvalues(5), 1e-10);
  EXPECT_GT(eigenvalues(6), 1e-4);
  const Eigen::MatrixXd psi = plasticLaplacianNullspace(Lsc.rows());
  EXPECT_LT((psi.transpose() * psi - Eigen::MatrixXd::Identity(6, 6)).norm(), 1e-14);
  for (int c = 0; c < 6; ++c) EXPECT_LT(applyPlasticLaplacian(Lsc, psi.col(c)).norm(), 1e-14);
}

TEST(PlasticLaplacian, OffDiagonalComponentsWeighSqrtTwo) {
  const Eigen::SparseMatrix<double> Lsc = tetAdjacencyLaplacian(cubeGridTets(2));
  const Eigen::Index m = Lsc.rows();
  const Eigen::VectorXd s = Eigen::VectorXd::Random(6 * m);
  const Eigen::VectorXd Ls = applyPlasticLaplacian(Lsc, s);
  double expected = 0.0;
  for (int c = 0; c < 6; ++c) {
    const double weight = (c == 1 || c == 2 || c == 4) ? 2.0 : 1.0;
    const Eigen::VectorXd sc = Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<6>>(s.data() + c, m);
    expected += weight * (Lsc * sc).squaredNorm();
  }
  EXPECT_NEAR(Ls.squaredNorm(), expected, 1e-12 * expected);  // sᵀL²s = Σ_c ξ_c² s_cᵀ Lsc² s_c
}

TEST(SmoothnessBaseSolver, InvertsLSquaredMinusNullspaceProjector) {
  const Eigen::SparseMatrix<double> Lsc = tetAdjacencyLaplacian(cubeGridTets(4));
  const Eigen::SparseMatrix<double> L = densePlasticLaplacian(Lsc).sparseView();
  const Eigen::MatrixXd psi = plasticLaplacianNullspace(Lsc.rows());
  const Eigen::MatrixXd B = Eigen::MatrixXd(L * L) - psi * psi.transpose();
  const SmoothnessBaseSolver solver(Lsc);
  const Eigen::MatrixXd h = Eigen::MatrixXd::Random(B.rows(), 5);
  const double error = (B * solver.solve(h) - h).norm() / h.norm();
  EXPECT_LT(error, 1e-9);
  RecordProperty("relative_residual", testing::PrintToString(error));
}

TEST(SmoothnessBaseSolver, SandwichMatchesExplicitProduct) {
  const Eigen::SparseMatrix<double> Lsc = tetAdjacencyLaplacian(cubeGridTets(3));
  const SmoothnessBaseSolver solver(Lsc);
  const Eigen::MatrixXd Z = Eigen::MatrixXd::Random(20, 6 * Lsc.rows());
  // Z B⁻¹ Zᵀ = Z (L²)⁺ Zᵀ − (Zψ)(Zψ)ᵀ.
  const Eigen::MatrixXd Zpsi = Z * plasticLaplacianNullspace(Lsc.rows());
  const Eigen::MatrixXd expected = Z * solver.solve(Z.transpose()) + Zpsi * Zpsi.transpose();
  EXPECT_LT((solver.sandwich(ConstraintJacobian(Z), Zpsi) - expected).norm() / expected.norm(), 1e-11);
}

TEST(SmoothnessBaseSolver, SingleTetHasOnlyTheNullspaceTerm) {
  const SmoothnessBaseSolver solver(tetAdjacencyLaplacian(MatrixX4i(cubeGridTets(1).topRows(1))));
  const Eigen::MatrixXd h = Eigen::MatrixXd::Random(6, 2);
  EXPECT_LT((solver.solve(h) + h).norm(), 1e-15);  // B = −I
}

TEST(SmoothnessBaseSolver, RejectsMeshesThatAreNotFaceConnected) {
  const MatrixX4i grid = cubeGridTets(2);
  MatrixX4i twoGrids(2 * grid.rows(), 4);
  twoGrids << grid, (grid.array() + 27).matrix();
  EXPECT_THROW(SmoothnessBaseSolver{tetAdjacencyLaplacian(twoGrids)}, BadInput);
  // A seventh tet touching the cube at one vertex only.
  MatrixX4i cornerTouch(7, 4);
  cornerTouch << cubeGridTets(1), 0, 100, 101, 102;
  EXPECT_THROW(SmoothnessBaseSolver{tetAdjacencyLaplacian(cornerTouch)}, BadInput);
  EXPECT_THROW(SmoothnessBaseSolver{Eigen::SparseMatrix<double>()}, BadInput);
}

TEST(PlasticLaplacian, RejectsNonManifoldFacesAndNegativeIndices) {
  MatrixX4i T(3, 4);
  T << 0, 1, 2, 3, 0, 1, 2, 4, 0, 1, 2, 5;
  EXPECT_THROW(tetAdjacencyLaplacian(T), BadInput);
  T(2, 3) = -1;
  EXPECT_THROW(tetAdjacencyLaplacian(T), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
