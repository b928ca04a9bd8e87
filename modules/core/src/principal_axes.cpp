#include "vesalius/core/principal_axes.h"

#include "vesalius/core/error.h"

#include <Eigen/Eigenvalues>

namespace vesalius {

PrincipalAxes principalAxes(const MatrixX3d& P) {
  if (P.rows() == 0) throw BadInput("", "principal axes of no points");
  PrincipalAxes a;
  a.centroid = P.colwise().mean().transpose();
  const MatrixX3d centred = P.rowwise() - a.centroid.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(centred.transpose() * centred / double(P.rows()));
  a.axes = eigen.eigenvectors().rowwise().reverse();  // Eigen sorts ascending
  a.variances = eigen.eigenvalues().reverse();
  if (a.axes.determinant() < 0) a.axes.col(2) *= -1;
  return a;
}

}  // namespace vesalius
