// J = dx/ds of the equilibrium (Wang et al. 2021, eq. 10) against finite differences of re-solved equilibria,
// attached (springs) and un-attached (rigid gauge).
#include "vesalius/fit/equilibrium_jacobian.h"

#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fem/point_springs.h"
#include "vesalius/fem/static_equilibrium.h"

#include "test_tets.h"

#include <gtest/gtest.h>

namespace vesalius::fit {
namespace {

struct Problem {
  TetMesh mesh = test::boxTets(4, 2, 2, 5.0);
  PlasticFem fem{mesh.V, mesh.T, StableNeoHookean::fromYoungPoisson(1.0, 0.45)};
  Eigen::VectorXd s;
  std::vector<PointConstraint> markers;  // a few material points, for the rows of Z
  Problem() {
    std::srand(3);
    s.resize(6 * mesh.T.rows());
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
      const double x = mesh.V.row(mesh.T(t, 0)).x() / 20.0;
      Vector6d p = identityPlasticStrain();
      p[0] += 0.4 * x;
      p[1] += 0.1 * x;
      p[5] -= 0.2 * x;
      s.segment<6>(6 * t) = p;
    }
    for (int k = 0; k < 5; ++k) {
      PointConstraint c;
      c.tet = (11 * k + 3) % int(mesh.T.rows());
      for (int i = 0; i < 4; ++i) c.vertices[i] = mesh.T(c.tet, i);
      c.weights = Eigen::Vector4d(0.1, 0.2, 0.3, 0.4);
      c.weight = 4.0;
      markers.push_back(c);
    }
  }
  // One end of the bar held by springs at its rest positions.
  PointSprings heldEnd() const {
    std::vector<PointConstraint> held;
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
      for (int i = 0; i < 4; ++i)
        if (mesh.V(mesh.T(t, i), 0) == 0.0) {
          PointConstraint c;
          c.tet = int(t);
          for (int j = 0; j < 4; ++j) c.vertices[j] = mesh.T(t, j);
          c.weights = Eigen::Vector4d::Unit(i);
          c.target = mesh.V.row(mesh.T(t, i)).transpose();
          held.push_back(c);
        }
    }
    return asSprings(held, 50.0);
  }
};

EquilibriumOptions tight() {
  EquilibriumOptions o;
  o.tolerance = 1e-11;
  return o;
}

TEST(EquilibriumJacobian, AttachedMatchesFiniteDifferences) {
  const Problem p;
  const PointSprings springs = p.heldEnd();
  const auto solve = [&](const Eigen::VectorXd& s) {
    return solveStaticEquilibrium(p.fem, s, springs, PlasticFem::flatten(p.mesh.V), tight()).x;
  };
  const Eigen::VectorXd x = solve(p.s);
  Eigen::SparseMatrix<double> K = p.fem.stiffness(x, p.s, false) + pointSpringHessian(springs, p.mesh.T, p.fem.vertexCount());
  const Eigen::SparseMatrix<double> G = p.fem.plasticForceJacobian(x, p.s);
  SparseCholesky cholesky;
  const EquilibriumJacobian J(K, G, x, nullptr, cholesky);

  const Eigen::VectorXd ds = 0.1 * Eigen::VectorXd::Random(p.s.size());
  const double h = 1e-5;
  const Eigen::VectorXd fd = (solve(p.s + h * ds) - solve(p.s - h * ds)) / (2 * h);
  const Eigen::VectorXd dx = J.apply(ds);
  EXPECT_LT((dx - fd).norm(), 1e-5 * fd.norm());

  const ConstraintJacobian Z = J.constraintJacobian(constraintRows(p.markers, p.fem.vertexCount()));
  const Eigen::VectorXd rowsFd = constraintRows(p.markers, p.fem.vertexCount()) * fd;
  EXPECT_LT((Z * ds - rowsFd).norm(), 1e-5 * rowsFd.norm());
}

TEST(EquilibriumJacobian, UnattachedInTheRigidGaugeMatchesFiniteDifferences) {
  const Problem p;
  const auto free = [&](const Eigen::VectorXd& s, const Eigen::VectorXd& start) {
    return solveStaticEquilibrium(p.fem, s, PointSprings{}, start, tight()).x;
  };
  const Eigen::VectorXd x = free(p.s, PlasticFem::flatten(p.mesh.V));
  const RigidGauge gauge(p.markers, p.mesh.V, x);
  const Eigen::SparseMatrix<double> K = p.fem.stiffness(x, p.s, false);
  const Eigen::SparseMatrix<double> G = p.fem.plasticForceJacobian(x, p.s);
  SparseCholesky cholesky;
  const EquilibriumJacobian J(K, G, x, &gauge, cholesky);

  const Eigen::VectorXd ds = 0.1 * Eigen::VectorXd::Random(p.s.size());
  const double h = 1e-4;  // the damped solver's noise dominates below
  const Eigen::VectorXd fd =
      (gauge.impose(free(p.s + h * ds, x)) - gauge.impose(free(p.s - h * ds, x))) / (2 * h);
  const Eigen::VectorXd dx = J.apply(ds);
  EXPECT_LT((dx - fd).norm(), 1e-5 * fd.norm());
  // dx keeps the gauge: the constrained points' centroid does not move.
  Eigen::Vector3d dc = Eigen::Vector3d::Zero();
  for (const auto& m : p.markers) dc += constrainedPoint(m, dx);
  EXPECT_LT(dc.norm(), 1e-9 * dx.norm());
}

}  // namespace
}  // namespace vesalius::fit
