#include "vesalius/fem/stable_neo_hookean.h"

#include "vesalius/core/error.h"

#include "fem_test_support.h"

#include <Eigen/Eigenvalues>

namespace vesalius {
namespace {

using Matrix9d = Eigen::Matrix<double, 9, 9>;
using test::centralDifferences;
using test::expectRelativeError;

const StableNeoHookean kMaterial = StableNeoHookean::fromYoungPoisson(10.0, 0.4);

Eigen::VectorXd vec(const Eigen::Matrix3d& F) { return Eigen::Map<const Eigen::VectorXd>(F.data(), 9); }
Eigen::Matrix3d unvec(const Eigen::VectorXd& f) { return Eigen::Map<const Eigen::Matrix3d>(f.data()); }

// A general F, one nearly flat (J = 0.01) and one inverted (J < 0).
std::vector<std::pair<std::string, Eigen::Matrix3d>> testGradients() {
  Eigen::Matrix3d general, flat, inverted;
  general << 1.2, 0.3, -0.1, 0.05, 0.9, 0.2, -0.15, 0.1, 1.4;
  flat << 1.0, 0.2, 0.0, 0.1, 1.1, 0.3, 0.0, 0.0, 0.01;
  inverted << -0.7, 0.2, 0.1, 0.1, 1.1, -0.3, 0.2, 0.05, 0.9;
  EXPECT_NEAR(flat.determinant(), 0.0111, 1e-3);
  EXPECT_LT(inverted.determinant(), 0);
  return {{"general", general}, {"nearlyFlat", flat}, {"inverted", inverted}};
}

TEST(StableNeoHookean, RestIsStressFreeWithZeroEnergyAlsoWhenRotated) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const Eigen::Matrix3d& F : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), Eigen::Matrix3d(R)}) {
    EXPECT_NEAR(kMaterial.energy(F), 0, 1e-14);
    EXPECT_LT(kMaterial.stress(F).norm(), 1e-13);
  }
}

TEST(StableNeoHookean, StressIsTheDerivativeOfEnergy) {
  for (const auto& [name, F] : testGradients()) {
    const Eigen::MatrixXd fd = centralDifferences(
        [](const Eigen::VectorXd& f) { return Eigen::VectorXd::Constant(1, kMaterial.energy(unvec(f))); }, vec(F),
        1e-6);
    expectRelativeError("P_" + name, vec(kMaterial.stress(F)).transpose(), fd, 1e-6);
  }
}

TEST(StableNeoHookean, StressDerivativeIsTheDerivativeOfStress) {
  for (const auto& [name, F] : testGradients()) {
    const Eigen::MatrixXd fd =
        centralDifferences([](const Eigen::VectorXd& f) { return vec(kMaterial.stress(unvec(f))); }, vec(F), 1e-6);
    const Matrix9d H = kMaterial.stressDerivative(F);
    expectRelativeError("dPdF_" + name, H, fd, 1e-6);
    EXPECT_LT((H - H.transpose()).norm(), 1e-12 * H.norm());
  }
}

TEST(StableNeoHookean, ProjectedStressDerivativeIsPsdAndExactWhereAlreadyPsd) {
  for (const auto& [name, F] : testGradients()) {
    const Matrix9d P = kMaterial.projectedStressDerivative(F);
    const double lowest = Eigen::SelfAdjointEigenSolver<Matrix9d>(P).eigenvalues().minCoeff();
    EXPECT_GT(lowest, -1e-12 * P.norm()) << name;
    if (name == "inverted") {  // the projection has work to do
      EXPECT_LT(Eigen::SelfAdjointEigenSolver<Matrix9d>(kMaterial.stressDerivative(F)).eigenvalues().minCoeff(),
                0);
    }
  }
  const Matrix9d H = kMaterial.stressDerivative(Eigen::Matrix3d::Identity());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix9d>(H).eigenvalues().minCoeff(), -1e-12 * H.norm());
  expectRelativeError("projectedAtRest", kMaterial.projectedStressDerivative(Eigen::Matrix3d::Identity()), H,
                      1e-12);
}

// At F = I the second derivative must be linear elasticity's: ε : C : ε = 2 μ_L ||ε||² + λ_L tr(ε)².
TEST(StableNeoHookean, LameReparameterizationMatchesLinearElasticity) {
  const double young = 10, poisson = 0.45;
  const StableNeoHookean m = StableNeoHookean::fromYoungPoisson(young, poisson);
  const double muLame = young / (2 * (1 + poisson));
  const double lambdaLame = young * poisson / ((1 + poisson) * (1 - 2 * poisson));
  Eigen::Matrix3d e;
  e << 0.3, 0.1, -0.2, 0.1, -0.5, 0.4, -0.2, 0.4, 0.7;
  const double quadratic = vec(e).dot(m.stressDerivative(Eigen::Matrix3d::Identity()) * vec(e));
  const double linear = 2 * muLame * e.squaredNorm() + lambdaLame * e.trace() * e.trace();
  EXPECT_NEAR(quadratic / linear, 1.0, 1e-12);
}

TEST(StableNeoHookean, RefusesImpossibleYoungPoisson) {
  EXPECT_THROW(StableNeoHookean::fromYoungPoisson(0, 0.3), BadInput);
  EXPECT_THROW(StableNeoHookean::fromYoungPoisson(1, 0.5), BadInput);
  EXPECT_THROW(StableNeoHookean::fromYoungPoisson(1, -1), BadInput);
}

}  // namespace
}  // namespace vesalius
