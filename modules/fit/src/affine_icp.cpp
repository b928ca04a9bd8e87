// Affine ICP (affine_icp.h).
#include "vesalius/fit/affine_icp.h"

#include "vesalius/core/triangle_tree.h"

#include <Eigen/Cholesky>

#include <vector>

namespace vesalius::fit {

TriMesh refineAffineIcp(TriMesh surface, const MatrixX3d& targets, const AffineIcpOptions& options) {
  if (targets.rows() < options.minTargets) return surface;
  for (int it = 0; it < options.iterations; ++it) {
    const std::vector<ClosestPoint> closest = TriangleTree(surface.V, surface.F).closest(targets);
    Eigen::MatrixXd X(targets.rows(), 4);
    for (Eigen::Index i = 0; i < targets.rows(); ++i) X.row(i) << closest[std::size_t(i)].point.transpose(), 1.0;
    const Eigen::LDLT<Eigen::Matrix4d> normal(X.transpose() * X);
    if (normal.info() != Eigen::Success || !(normal.vectorD().array() > 1e-12 * normal.vectorD().maxCoeff()).all())
      break;
    const Eigen::Matrix<double, 4, 3> A = normal.solve(X.transpose() * targets);
    surface.V = (surface.V * A.topRows<3>()).rowwise() + A.row(3);
  }
  return surface;
}

}  // namespace vesalius::fit
