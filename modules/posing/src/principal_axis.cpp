#include "vesalius/posing/principal_axis.h"

#include "vesalius/core/error.h"

#include <Eigen/Eigenvalues>

namespace vesalius::posing {

Eigen::Vector3d principalAxis(const MatrixX3d& P, const Eigen::Vector3d& towards) {
  if (P.rows() < 2) throw BadInput("", "a principal axis needs at least two points");
  const MatrixX3d Q = P.rowwise() - P.colwise().mean();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(Q.transpose() * Q / double(P.rows()));
  const Eigen::Vector3d lambda = eig.eigenvalues();  // ascending
  if (!(lambda[2] > 0)) throw BadInput("", "a principal axis needs two distinct points");
  if (lambda[2] - lambda[1] <= 1e-9 * lambda[2]) throw BadInput("", "the points have no single longest axis");
  const Eigen::Vector3d axis = eig.eigenvectors().col(2);
  return axis.dot(towards) < 0 ? Eigen::Vector3d(-axis) : axis;
}

}  // namespace vesalius::posing
