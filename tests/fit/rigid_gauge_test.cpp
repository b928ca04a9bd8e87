#include "vesalius/fit/rigid_gauge.h"

#include "vesalius/fit/polar_derivatives.h"

#include "test_tets.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace vesalius::fit {
namespace {

struct Scene {
  TetMesh mesh = test::boxTets(3, 2, 2, 10.0);
  Eigen::VectorXd x;
  std::vector<PointConstraint> D;
  Scene() {
    std::srand(7);
    MatrixX3d V = mesh.V + 2.0 * MatrixX3d::Random(mesh.V.rows(), 3);
    x.resize(3 * V.rows());
    for (Eigen::Index v = 0; v < V.rows(); ++v) x.segment<3>(3 * v) = 1.2 * V.row(v).transpose();
    for (int k = 0; k < 8; ++k) {
      PointConstraint c;
      const Eigen::Index t = (7 * k) % mesh.T.rows();
      for (int i = 0; i < 4; ++i) c.vertices[i] = mesh.T(t, i);
      c.weights = (Eigen::Vector4d::Random().array() + 1.5).matrix();
      c.weights /= c.weights.sum();
      D.push_back(c);
    }
  }
};

Eigen::VectorXd moved(const Eigen::VectorXd& x, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Eigen::VectorXd y(x.size());
  for (Eigen::Index v = 0; v < x.size() / 3; ++v) y.segment<3>(3 * v) = R * x.segment<3>(3 * v) + t;
  return y;
}

TEST(RigidGauge, ImposingItUndoesAnyRigidMotion) {
  const Scene s;
  const RigidGauge gauge(s.D, s.mesh.V, s.x);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::VectorXd back = gauge.impose(moved(s.x, R, Eigen::Vector3d(5, -3, 8)));
  EXPECT_LT((back - s.x).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(RigidGauge, ConstraintJacobianMatchesFiniteDifferences) {
  const Scene s;
  const RigidGauge gauge(s.D, s.mesh.V, s.x);
  const Eigen::MatrixXd C = gauge.constraintJacobian(s.x);
  const Eigen::VectorXd dx = Eigen::VectorXd::Random(s.x.size());
  const double h = 1e-6;
  // The gauge of x ± h dx seen from the gauge of x: the rigid motion that imposing it applies.
  const auto centroid = [&](const Eigen::VectorXd& y) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const auto& p : s.D) c += constrainedPoint(p, y);
    return Eigen::Vector3d(c / double(s.D.size()));
  };
  const auto rotation = [&](const Eigen::VectorXd& y) {
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Xbar = Eigen::Vector3d::Zero();
    for (const auto& p : s.D) {
      Eigen::Vector3d X = Eigen::Vector3d::Zero();
      for (int i = 0; i < 4; ++i) X += p.weights[i] * s.mesh.V.row(p.vertices[i]).transpose();
      Xbar += X / double(s.D.size());
    }
    for (const auto& p : s.D) {
      Eigen::Vector3d X = Eigen::Vector3d::Zero();
      for (int i = 0; i < 4; ++i) X += p.weights[i] * s.mesh.V.row(p.vertices[i]).transpose();
      M += constrainedPoint(p, y) * (X - Xbar).transpose();
    }
    return polarRotation(M);
  };
  const Eigen::Vector3d dc = (centroid(s.x + h * dx) - centroid(s.x - h * dx)) / (2 * h);
  const Eigen::Matrix3d dR = (rotation(s.x + h * dx) - rotation(s.x - h * dx)) / (2 * h);
  const Eigen::Matrix3d skew = rotation(s.x).transpose() * dR;
  Eigen::Matrix<double, 6, 1> expected;
  expected << dc, skew(2, 1), skew(0, 2), skew(1, 0);
  const Eigen::Matrix<double, 6, 1> got = C * dx;
  EXPECT_LT((got - expected).norm(), 1e-6 * expected.norm());
}

TEST(RigidGauge, RigidModesAreTranslationsAndRotations) {
  const Scene s;
  const Eigen::MatrixXd N = rigidModes(s.x);
  const double h = 1e-7;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(h, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (Eigen::Index v = 0; v < s.x.size() / 3; ++v) c += s.x.segment<3>(3 * v) / double(s.x.size() / 3);
  const Eigen::VectorXd turned = moved(s.x, R, c - R * c);
  EXPECT_LT(((turned - s.x) / h - N.col(5)).cwiseAbs().maxCoeff(), 1e-5);
  EXPECT_DOUBLE_EQ(N.col(0).segment<3>(0)[0], 1.0);
}

}  // namespace
}  // namespace vesalius::fit
