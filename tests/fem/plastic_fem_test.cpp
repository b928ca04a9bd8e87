#include "vesalius/fem/plastic_fem.h"

#include "vesalius/core/error.h"

#include "fem_test_support.h"

#include <Eigen/Eigenvalues>
#include <tbb/global_control.h>

namespace vesalius {
namespace {

using test::centralDifferences;
using test::expectRelativeError;

const StableNeoHookean kMaterial = StableNeoHookean::fromYoungPoisson(10.0, 0.45);

// A 2x2x2-cube box of 5 mm cubes (48 tets) with jittered vertices, random SPD plastic strains, and a
// deformed state that is the plastic-free template sheared, stretched and jittered.
struct Scene {
  TetMesh mesh = test::boxTets(2, 2, 2, 5.0);
  Eigen::VectorXd s, x;
  Scene() {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> jitter(-0.6, 0.6);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
      for (int k = 0; k < 3; ++k) mesh.V(i, k) += jitter(rng);
    s.resize(6 * mesh.T.rows());
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
      s.segment<6>(6 * t) = test::randomPlasticStrain(rng, Eigen::Vector3d(1.3, 0.9, 1.1).asDiagonal(), 0.15);
    Eigen::Matrix3d A;
    A << 1.2, 0.15, 0, -0.1, 0.95, 0.2, 0.05, 0, 1.05;
    x = PlasticFem::flatten(mesh.V * A.transpose());
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.3 * jitter(rng);
  }
  PlasticFem fem() const { return PlasticFem(mesh.V, mesh.T, kMaterial); }
};

TEST(PlasticFem, AssembledDerivativesMatchFiniteDifferences) {
  const Scene scene;
  const PlasticFem fem = scene.fem();
  const auto energy = [&](const Eigen::VectorXd& y) {
    return Eigen::VectorXd::Constant(1, fem.energy(y, scene.s));
  };
  const auto gradientInX = [&](const Eigen::VectorXd& y) { return fem.gradient(y, scene.s); };
  const auto gradientInS = [&](const Eigen::VectorXd& p) { return fem.gradient(scene.x, p); };
  expectRelativeError("femGradient", fem.gradient(scene.x, scene.s).transpose(),
                      centralDifferences(energy, scene.x, 1e-5), 1e-6);
  const Eigen::MatrixXd K = fem.stiffness(scene.x, scene.s, false);
  expectRelativeError("femStiffness", K, centralDifferences(gradientInX, scene.x, 1e-5), 1e-6);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  expectRelativeError("femPlasticForceJacobian", Eigen::MatrixXd(fem.plasticForceJacobian(scene.x, scene.s)),
                      centralDifferences(gradientInS, scene.s, 1e-6), 1e-6);
}

TEST(PlasticFem, ProjectedStiffnessIsPsdWithAFixedPattern) {
  const Scene scene;
  const PlasticFem fem = scene.fem();
  const Eigen::SparseMatrix<double> projected = fem.stiffness(scene.x, scene.s, true);
  const Eigen::SparseMatrix<double> exact = fem.stiffness(scene.x, scene.s, false);
  const Eigen::SparseMatrix<double> atRest = fem.stiffness(PlasticFem::flatten(scene.mesh.V), scene.s, true);
  const Eigen::MatrixXd P = projected;
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff(), -1e-12 * P.norm());
  EXPECT_LT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(exact)).eigenvalues().minCoeff(),
            -1e-6 * P.norm())
      << "this state should need the projection";
  for (const auto* other : {&exact, &atRest}) {
    ASSERT_EQ(other->nonZeros(), projected.nonZeros());
    EXPECT_TRUE(std::equal(projected.innerIndexPtr(), projected.innerIndexPtr() + projected.nonZeros(),
                           other->innerIndexPtr()));
    EXPECT_TRUE(std::equal(projected.outerIndexPtr(), projected.outerIndexPtr() + projected.cols() + 1,
                           other->outerIndexPtr()));
  }
}

TEST(PlasticFem, RestStateIsForceFreeAndRigidMotionsChangeNothing) {
  const Scene scene;
  const PlasticFem fem = scene.fem();
  const Eigen::VectorXd rest = PlasticFem::flatten(scene.mesh.V);
  const Eigen::VectorXd identity = identityPlasticStrain().replicate(fem.tetCount(), 1);
  EXPECT_LT(std::abs(fem.energy(rest, identity)), 1e-12 * kMaterial.mu * fem.restVolumes().sum());
  EXPECT_LT(fem.gradient(rest, identity).norm(), 1e-12);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(2.0, Eigen::Vector3d(0.3, 1, -0.4).normalized()).toRotationMatrix();
  MatrixX3d moved = PlasticFem::unflatten(scene.x) * R.transpose();
  moved.rowwise() += Eigen::RowVector3d(100, -50, 7);
  const double e = fem.energy(scene.x, scene.s);
  EXPECT_NEAR(fem.energy(PlasticFem::flatten(moved), scene.s), e, 1e-12 * e);
}

TEST(PlasticFem, ResultsDoNotDependOnThreadCount) {
  const Scene scene;
  const PlasticFem fem = scene.fem();
  const Eigen::VectorXd g = fem.gradient(scene.x, scene.s);
  const Eigen::MatrixXd K = fem.stiffness(scene.x, scene.s, true);
  const double e = fem.energy(scene.x, scene.s);
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(fem.energy(scene.x, scene.s), e);
  EXPECT_EQ(fem.gradient(scene.x, scene.s), g);
  EXPECT_EQ(Eigen::MatrixXd(fem.stiffness(scene.x, scene.s, true)), K);
}

TEST(PlasticFem, SizesVolumesAndFlattening) {
  const Scene scene;
  const PlasticFem fem = scene.fem();
  EXPECT_EQ(fem.vertexCount(), 27);
  EXPECT_EQ(fem.tetCount(), 48);
  EXPECT_LT((fem.restVolumes() - tetVolumes(scene.mesh.V, scene.mesh.T)).norm(), 1e-12);
  EXPECT_EQ(PlasticFem::unflatten(PlasticFem::flatten(scene.mesh.V)), scene.mesh.V);
  EXPECT_EQ(PlasticFem::flatten(scene.mesh.V).segment<3>(3), scene.mesh.V.row(1).transpose());
  EXPECT_THROW(fem.energy(scene.x.head(9), scene.s), BadInput);
}

TEST(PlasticFem, RefusesInvertedTetsAndBadIndices) {
  TetMesh mesh = test::boxTets(1, 1, 1, 1.0);
  std::swap(mesh.T(3, 0), mesh.T(3, 1));
  EXPECT_THROW(PlasticFem(mesh.V, mesh.T, kMaterial), BadInput);
  mesh = test::boxTets(1, 1, 1, 1.0);
  mesh.T(2, 2) = 8;
  EXPECT_THROW(PlasticFem(mesh.V, mesh.T, kMaterial), BadInput);
  mesh = test::boxTets(1, 1, 1, 1.0);
  mesh.V.row(mesh.T(0, 3)) = mesh.V.row(mesh.T(0, 2));  // flattens tet 0
  EXPECT_THROW(PlasticFem(mesh.V, mesh.T, kMaterial), BadInput);
  EXPECT_THROW(PlasticFem(mesh.V, MatrixX4i(0, 4), kMaterial), BadInput);
  EXPECT_THROW(PlasticFem(test::boxTets(1, 1, 1, 1.0).V, mesh.T, StableNeoHookean{0, 1}), BadInput);
}

}  // namespace
}  // namespace vesalius
