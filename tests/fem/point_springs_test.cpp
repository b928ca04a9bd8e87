#include "vesalius/fem/point_springs.h"

#include "vesalius/core/error.h"
#include "vesalius/fem/plastic_fem.h"

#include "fem_test_support.h"

namespace vesalius {
namespace {

using test::centralDifferences;
using test::expectRelativeError;

struct Scene {
  TetMesh mesh = test::boxTets(2, 1, 1, 4.0);
  PointSprings springs;
  Eigen::VectorXd x;
  Scene() {
    springs.points = {{0, Eigen::Vector4d(0.1, 0.2, 0.3, 0.4)},
                      {5, Eigen::Vector4d(1, 0, 0, 0)},
                      {9, Eigen::Vector4d(0.25, 0.25, 0.25, 0.25)},
                      {9, Eigen::Vector4d(0.7, 0.1, 0.1, 0.1)}};
    springs.targets.resize(4, 3);
    springs.targets << 1, 2, 3, -1, 0, 5, 8, 8, 1, 3, 3, 3;
    springs.stiffness = Eigen::Vector4d(10, 0.5, 3, 0);
    x = PlasticFem::flatten(mesh.V) + Eigen::VectorXd::LinSpaced(3 * mesh.V.rows(), -1, 2);
  }
};

TEST(PointSprings, DerivativesMatchFiniteDifferences) {
  const Scene sc;
  const auto energy = [&](const Eigen::VectorXd& y) {
    return Eigen::VectorXd::Constant(1, pointSpringEnergy(sc.springs, sc.mesh.T, y));
  };
  const auto gradient = [&](const Eigen::VectorXd& y) { return pointSpringGradient(sc.springs, sc.mesh.T, y); };
  expectRelativeError("springGradient", pointSpringGradient(sc.springs, sc.mesh.T, sc.x).transpose(),
                      centralDifferences(energy, sc.x, 1e-4), 1e-8);
  expectRelativeError("springHessian",
                      Eigen::MatrixXd(pointSpringHessian(sc.springs, sc.mesh.T, int(sc.mesh.V.rows()))),
                      centralDifferences(gradient, sc.x, 1e-4), 1e-8);
}

TEST(PointSprings, VertexSpringAtItsTargetHasNoEnergy) {
  Scene sc;
  sc.springs.points = {{3, Eigen::Vector4d(0, 0, 1, 0)}};
  sc.springs.targets = sc.mesh.V.row(sc.mesh.T(3, 2));
  sc.springs.stiffness = Eigen::VectorXd::Constant(1, 100);
  EXPECT_EQ(pointSpringEnergy(sc.springs, sc.mesh.T, PlasticFem::flatten(sc.mesh.V)), 0);
}

TEST(PointSprings, RefusesSpringsThatDoNotFit) {
  Scene sc;
  sc.springs.points[2].tet = int(sc.mesh.T.rows());
  EXPECT_THROW(pointSpringEnergy(sc.springs, sc.mesh.T, sc.x), BadInput);
  sc = Scene();
  sc.springs.stiffness.resize(3);
  EXPECT_THROW(pointSpringGradient(sc.springs, sc.mesh.T, sc.x), BadInput);
  sc = Scene();
  sc.springs.stiffness[1] = -1;
  EXPECT_THROW(pointSpringHessian(sc.springs, sc.mesh.T, int(sc.mesh.V.rows())), BadInput);
}

}  // namespace
}  // namespace vesalius
