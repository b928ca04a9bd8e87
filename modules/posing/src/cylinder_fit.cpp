#include "vesalius/posing/cylinder_fit.h"

#include "vesalius/core/error.h"

#include <Eigen/Geometry>
#include <Eigen/QR>

#include <cmath>

namespace vesalius::posing {
namespace {

struct Axis {
  Eigen::Vector3d point, direction;
  double radius;
};

// Two unit vectors completing d to an orthonormal basis.
std::pair<Eigen::Vector3d, Eigen::Vector3d> across(const Eigen::Vector3d& d) {
  const Eigen::Vector3d u = d.unitOrthogonal();
  return {u, d.cross(u)};
}

Eigen::VectorXd residuals(const MatrixX3d& Q, const Axis& a) {
  const MatrixX3d W = Q.rowwise() - a.point.transpose();
  const MatrixX3d across = W - (W * a.direction) * a.direction.transpose();
  return across.rowwise().norm().array() - a.radius;
}

// Kåsa's circle fit of the points projected on the plane across `direction` (Q centred at its mean).
Axis circleFit(const MatrixX3d& Q, const Eigen::Vector3d& direction) {
  const auto [u, v] = across(direction);
  Eigen::MatrixXd A(Q.rows(), 3);
  A.col(0) = 2 * Q * u;
  A.col(1) = 2 * Q * v;
  A.col(2).setOnes();
  const Eigen::VectorXd b = A.leftCols<2>().rowwise().squaredNorm() / 4;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 3) throw BadInput("", "a cylinder fit needs points spread around its axis");
  const Eigen::Vector3d x = qr.solve(b);
  return {x[0] * u + x[1] * v, direction, std::sqrt(std::max(0.0, x[2] + x[0] * x[0] + x[1] * x[1]))};
}

// Jacobian of the residuals in (tilt towards u, tilt towards v, shift along u, shift along v, radius):
// with w = p − c and n the unit vector from the axis to p, ∂r/∂c = −n and ∂r/∂d = −(w·d) n, both taken
// across d (n ⟂ d).
Eigen::MatrixXd jacobian(const MatrixX3d& Q, const Axis& a, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  Eigen::MatrixXd J(Q.rows(), 5);
  for (Eigen::Index i = 0; i < Q.rows(); ++i) {
    const Eigen::Vector3d w = Q.row(i).transpose() - a.point;
    const double along = w.dot(a.direction);
    const Eigen::Vector3d q = w - along * a.direction;
    const Eigen::Vector3d n = q / std::max(q.norm(), 1e-300);
    J.row(i) << -along * n.dot(u), -along * n.dot(v), -n.dot(u), -n.dot(v), -1.0;
  }
  return J;
}

Axis moved(const Axis& a, const Eigen::Matrix<double, 5, 1>& step, const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return {a.point + step[2] * u + step[3] * v, (a.direction + step[0] * u + step[1] * v).normalized(), a.radius + step[4]};
}

}  // namespace

CylinderFit fitCylinder(const MatrixX3d& P, const Eigen::Vector3d& axisGuess, const CylinderFitOptions& options) {
  if (P.rows() < 5) throw BadInput("", "a cylinder fit needs at least 5 points, got " + std::to_string(P.rows()));
  if (!(axisGuess.norm() > 0)) throw BadInput("", "a cylinder fit needs a nonzero axis guess");
  const Eigen::RowVector3d mean = P.colwise().mean();
  const MatrixX3d Q = P.rowwise() - mean;
  Axis a = circleFit(Q, axisGuess.normalized());
  double cost = residuals(Q, a).squaredNorm(), damping = 1e-3;
  for (int it = 0; it < options.maxIterations && damping < 1e12; ++it) {
    // Keep the axis point nearest the mean, where turning the axis moves the points least.
    a.point -= a.point.dot(a.direction) * a.direction;
    const auto [u, v] = across(a.direction);
    const Eigen::MatrixXd J = jacobian(Q, a, u, v);
    const Eigen::VectorXd r = residuals(Q, a);
    Eigen::Matrix<double, 5, 5> H = J.transpose() * J;
    H.diagonal() *= 1 + damping;
    const Eigen::Matrix<double, 5, 1> step = H.ldlt().solve(-J.transpose() * r);
    const Axis next = moved(a, step, u, v);
    const double nextCost = residuals(Q, next).squaredNorm();
    if (!(nextCost <= cost)) {
      damping *= 10;
      continue;
    }
    a = next;
    cost = nextCost;
    damping = std::max(damping / 10, 1e-12);
    if (step.head<2>().norm() * a.radius + step.tail<3>().norm() <= options.tolerance * a.radius) break;
  }
  a.point -= a.point.dot(a.direction) * a.direction;
  CylinderFit fit;
  fit.axis = a.direction.dot(axisGuess) < 0 ? Eigen::Vector3d(-a.direction) : a.direction;
  fit.point = a.point + mean.transpose();
  fit.radius = a.radius;
  fit.rmsResidual = std::sqrt(residuals(Q, a).squaredNorm() / double(Q.rows()));
  return fit;
}

}  // namespace vesalius::posing
