#include "vesalius/posing/sphere_fit.h"

#include "vesalius/core/error.h"

#include <Eigen/QR>

#include <cmath>

namespace vesalius::posing {
namespace {

// Kåsa's fit of points centred at their mean (conditioning: |p|² is then of the sphere's size).
SphereFit algebraicFit(const MatrixX3d& Q) {
  Eigen::MatrixXd A(Q.rows(), 4);
  A.leftCols<3>() = 2 * Q;
  A.col(3).setOnes();
  const Eigen::VectorXd b = Q.rowwise().squaredNorm();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 4) throw BadInput("", "a sphere fit needs at least 4 points not on one plane");
  const Eigen::Vector4d x = qr.solve(b);
  SphereFit fit;
  fit.centre = x.head<3>();
  fit.radius = std::sqrt(std::max(0.0, x[3] + fit.centre.squaredNorm()));
  return fit;
}

// One Gauss–Newton step on r_i = |q_i − c| − r; returns the step (dc, dr).
Eigen::Vector4d gaussNewtonStep(const MatrixX3d& Q, const SphereFit& fit) {
  Eigen::MatrixXd J(Q.rows(), 4);
  Eigen::VectorXd residual(Q.rows());
  for (Eigen::Index i = 0; i < Q.rows(); ++i) {
    const Eigen::Vector3d d = Q.row(i).transpose() - fit.centre;
    const double n = std::max(d.norm(), 1e-300);
    J.row(i) << -d.transpose() / n, -1.0;
    residual[i] = n - fit.radius;
  }
  return J.colPivHouseholderQr().solve(-residual);
}

}  // namespace

SphereFit fitSphere(const MatrixX3d& P, const SphereFitOptions& options) {
  if (P.rows() < 4) throw BadInput("", "a sphere fit needs at least 4 points, got " + std::to_string(P.rows()));
  const Eigen::RowVector3d mean = P.colwise().mean();
  const MatrixX3d Q = P.rowwise() - mean;
  SphereFit fit = algebraicFit(Q);
  for (int it = 0; it < options.maxIterations; ++it) {
    const Eigen::Vector4d step = gaussNewtonStep(Q, fit);
    fit.centre += step.head<3>();
    fit.radius += step[3];
    if (step.norm() <= options.tolerance * fit.radius) break;
  }
  fit.rmsResidual = std::sqrt(((Q.rowwise() - fit.centre.transpose()).rowwise().norm().array() - fit.radius)
                                  .square().mean());
  fit.centre += mean.transpose();
  return fit;
}

}  // namespace vesalius::posing
