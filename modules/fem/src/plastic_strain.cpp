#include "vesalius/fem/plastic_strain.h"

#include <Eigen/Eigenvalues>

namespace vesalius {
namespace {

// Row and column of the upper-triangle entry each parameter s_i sets.
constexpr int kRow[6] = {0, 0, 0, 1, 1, 2};
constexpr int kCol[6] = {0, 1, 2, 1, 2, 2};

}  // namespace

Eigen::Matrix3d plasticStrainMatrix(const Vector6d& s) {
  Eigen::Matrix3d F;
  for (int i = 0; i < 6; ++i) F(kRow[i], kCol[i]) = F(kCol[i], kRow[i]) = s[i];
  return F;
}

Vector6d plasticStrainParameters(const Eigen::Matrix3d& symmetric) {
  Vector6d s;
  for (int i = 0; i < 6; ++i) s[i] = 0.5 * (symmetric(kRow[i], kCol[i]) + symmetric(kCol[i], kRow[i]));
  return s;
}

Vector6d identityPlasticStrain() { return plasticStrainParameters(Eigen::Matrix3d::Identity()); }

Eigen::Matrix<double, 9, 6> plasticStrainJacobian() {
  Eigen::Matrix<double, 9, 6> Y = Eigen::Matrix<double, 9, 6>::Zero();
  for (int i = 0; i < 6; ++i) Y(kRow[i] + 3 * kCol[i], i) = Y(kCol[i] + 3 * kRow[i], i) = 1;
  return Y;
}

Vector6d clampPlasticStrain(const Vector6d& s, double floor) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(plasticStrainMatrix(s));
  if (eig.eigenvalues().minCoeff() >= floor) return s;
  const Eigen::Vector3d clamped = eig.eigenvalues().cwiseMax(floor);
  return plasticStrainParameters(eig.eigenvectors() * clamped.asDiagonal() * eig.eigenvectors().transpose());
}

}  // namespace vesalius
