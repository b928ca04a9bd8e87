// A known smooth anisotropic plastic field (Wang et al. 2021, Fig. 21's ground truth) used by the fit's
// validation test and its benchmark.
#pragma once

#include "vesalius/fem/plastic_strain.h"

#include "vesalius/core/mesh.h"

#include <cmath>

namespace vesalius::test {

// Fp(X) = I + a(X) u uᵀ + b(X) (v wᵀ + w vᵀ) per tet (6#T, tet-major): a stretch up to 1.6 along an oblique
// axis u growing across the template's box, and a shear between y and z varying along z.
inline Eigen::VectorXd knownPlasticField(const TetMesh& m) {
  const Eigen::Vector3d u = Eigen::Vector3d(1, 0.3, 0.2).normalized(), v(0, 1, 0), w(0, 0, 1);
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff(), size = m.V.colwise().maxCoeff() - lo;
  Eigen::VectorXd s(6 * m.T.rows());
  for (Eigen::Index t = 0; t < m.T.rows(); ++t) {
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int i = 0; i < 4; ++i) c += m.V.row(m.T(t, i)) / 4;
    const Eigen::RowVector3d q = (c - lo).cwiseQuotient(size);
    s.segment<6>(6 * t) = plasticStrainParameters(Eigen::Matrix3d::Identity() + 0.6 * q.x() * u * u.transpose() +
                                                  0.15 * std::sin(3.0 * q.z()) * (v * w.transpose() + w * v.transpose()));
  }
  return s;
}

}  // namespace vesalius::test
