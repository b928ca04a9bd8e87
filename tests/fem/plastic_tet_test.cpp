#include "vesalius/fem/plastic_tet.h"

#include "vesalius/core/error.h"

#include "fem_test_support.h"

#include <Eigen/Eigenvalues>

namespace vesalius {
namespace {

using Corners = Eigen::Matrix<double, 4, 3>;
using test::centralDifferences;
using test::expectRelativeError;
using Stiffness = PlasticTetBlocks::Stiffness;

const StableNeoHookean kMaterial = StableNeoHookean::fromYoungPoisson(10.0, 0.4);

Corners restCorners() {
  Corners c;
  c << 0.1, -0.2, 0.0, 10.3, 0.4, -0.5, 1.2, 9.1, 0.3, -0.4, 1.5, 11.0;  // mm
  return c;
}

Eigen::VectorXd flat(const Corners& c) {
  const Eigen::Matrix<double, 3, 4> t = c.transpose();
  return Eigen::Map<const Eigen::VectorXd>(t.data(), 12);
}
Corners unflat(const Eigen::VectorXd& x) {
  return Eigen::Map<const Eigen::Matrix<double, 3, 4>>(x.data()).transpose();
}

// A deformed tet and a plastic strain, neither near identity.
struct Case {
  PlasticTetRest rest = plasticTetRest(restCorners());
  Corners x;
  Vector6d s;
  Case() {
    Eigen::Matrix3d A;
    A << 1.3, 0.2, -0.1, -0.3, 0.8, 0.25, 0.1, -0.2, 1.1;
    x = restCorners() * A.transpose();
    x.rowwise() += Eigen::RowVector3d(2, -1, 3);
    x(2, 1) += 0.7;
    std::mt19937 rng(7);
    Eigen::Matrix3d centre = Eigen::Vector3d(1.4, 0.8, 1.1).asDiagonal();
    s = test::randomPlasticStrain(rng, centre, 0.2);
  }
  PlasticTetDerivatives at(const Corners& y, const Vector6d& p, PlasticTetBlocks blocks = {}) const {
    return plasticTetDerivatives(rest, y, p, kMaterial, blocks);
  }
};

TEST(PlasticTet, GradientAndStiffnessMatchFiniteDifferences) {
  const Case c;
  const auto energy = [&](const Eigen::VectorXd& y) {
    return Eigen::VectorXd::Constant(1, c.at(unflat(y), c.s).energy);
  };
  const auto gradient = [&](const Eigen::VectorXd& y) { return Eigen::VectorXd(c.at(unflat(y), c.s).gradient); };
  PlasticTetBlocks blocks;
  blocks.stiffness = Stiffness::exact;
  const PlasticTetDerivatives d = c.at(c.x, c.s, blocks);
  expectRelativeError("tetGradient", d.gradient.transpose(), centralDifferences(energy, flat(c.x), 1e-5), 1e-6);
  expectRelativeError("tetStiffness", d.stiffness, centralDifferences(gradient, flat(c.x), 1e-5), 1e-6);
}

TEST(PlasticTet, PlasticDerivativesMatchFiniteDifferences) {
  const Case c;
  PlasticTetBlocks blocks;
  blocks.mixed = blocks.plastic = true;
  const PlasticTetDerivatives d = c.at(c.x, c.s, blocks);
  const auto energy = [&](const Eigen::VectorXd& p) { return Eigen::VectorXd::Constant(1, c.at(c.x, p).energy); };
  const auto gradient = [&](const Eigen::VectorXd& p) { return Eigen::VectorXd(c.at(c.x, p).gradient); };
  const auto plastic = [&](const Eigen::VectorXd& p) {
    return Eigen::VectorXd(c.at(c.x, p, blocks).plasticGradient);
  };
  const auto plasticInX = [&](const Eigen::VectorXd& y) {
    return Eigen::VectorXd(c.at(unflat(y), c.s, blocks).plasticGradient);
  };
  expectRelativeError("tetMixed", d.mixed, centralDifferences(gradient, c.s, 1e-6), 1e-6);
  expectRelativeError("tetMixedFromPlasticGradient", d.mixed.transpose(),
                      centralDifferences(plasticInX, flat(c.x), 1e-5), 1e-6);
  expectRelativeError("tetPlasticGradient", d.plasticGradient.transpose(), centralDifferences(energy, c.s, 1e-6),
                      1e-6);
  expectRelativeError("tetPlasticHessian", d.plasticHessian, centralDifferences(plastic, c.s, 1e-6), 1e-6);
}

TEST(PlasticTet, ProjectedStiffnessIsPsdAndExactAtRest) {
  const Case c;
  PlasticTetBlocks projected, exact;
  projected.stiffness = Stiffness::projected;
  exact.stiffness = Stiffness::exact;
  const Matrix12d K = c.at(c.x, c.s, projected).stiffness;
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix12d>(K).eigenvalues().minCoeff(), -1e-12 * K.norm());
  const Vector6d id = identityPlasticStrain();
  expectRelativeError("tetProjectedAtRest", c.at(restCorners(), id, projected).stiffness,
                      c.at(restCorners(), id, exact).stiffness, 1e-12);
}

TEST(PlasticTet, EnergyIsRigidInvariantAndZeroAtThePlasticRestShape) {
  const Case c;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  Corners moved = c.x * R.transpose();
  moved.rowwise() += Eigen::RowVector3d(-30, 4, 12);
  const double e = c.at(c.x, c.s).energy;
  EXPECT_GT(e, 0);
  EXPECT_NEAR(c.at(moved, c.s).energy, e, 1e-12 * e);

  const PlasticTetDerivatives atRest = c.at(restCorners(), identityPlasticStrain());
  EXPECT_LT(std::abs(atRest.energy), 1e-12 * kMaterial.mu * c.rest.volume);
  EXPECT_LT(atRest.gradient.norm(), 1e-12);
  // Fp applied to the template, then rotated: its own rest shape.
  const Corners plasticRest = restCorners() * plasticStrainMatrix(c.s) * R.transpose();
  const PlasticTetDerivatives atPlasticRest = c.at(plasticRest, c.s);
  EXPECT_LT(std::abs(atPlasticRest.energy), 1e-12 * e);
  EXPECT_LT(atPlasticRest.gradient.norm(), 1e-12 * c.at(c.x, c.s).gradient.norm());
  EXPECT_NEAR(plasticTetJacobian(c.rest, plasticRest, c.s), 1.0, 1e-12);
}

TEST(PlasticTet, RefusesInvertedOrFlatRestTets) {
  Corners inverted = restCorners();
  inverted.row(1).swap(inverted.row(2));
  EXPECT_THROW(plasticTetRest(inverted), BadInput);
  Corners flatTet = restCorners();
  flatTet.row(3) = (flatTet.row(0) + flatTet.row(1) + flatTet.row(2)) / 3;
  EXPECT_THROW(plasticTetRest(flatTet), BadInput);
  Corners nan = restCorners();
  nan(2, 2) = std::nan("");
  EXPECT_THROW(plasticTetRest(nan), BadInput);
}

}  // namespace
}  // namespace vesalius
