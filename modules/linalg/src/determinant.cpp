#include "vesalius/linalg/determinant.h"

#include <Eigen/Geometry>

namespace vesalius {
namespace {

// [v]x: the matrix of u -> v x u.
Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

}  // namespace

Eigen::Matrix3d determinantGradient(const Eigen::Matrix3d& F) {
  Eigen::Matrix3d g;
  g.col(0) = F.col(1).cross(F.col(2));
  g.col(1) = F.col(2).cross(F.col(0));
  g.col(2) = F.col(0).cross(F.col(1));
  return g;
}

Eigen::Matrix<double, 9, 9> determinantHessian(const Eigen::Matrix3d& F) {
  // d(f1 x f2)/df1 = -[f2]x, d(f1 x f2)/df2 = [f1]x, and cyclically.
  Eigen::Matrix<double, 9, 9> H = Eigen::Matrix<double, 9, 9>::Zero();
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const Eigen::Matrix3d c = crossMatrix(F.col(k));
    H.block<3, 3>(3 * i, 3 * j) = -c;
    H.block<3, 3>(3 * j, 3 * i) = c;
  }
  return H;
}

}  // namespace vesalius
