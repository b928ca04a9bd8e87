#include "vesalius/fit/point_constraints.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"

#include <cmath>

namespace vesalius::fit {

Eigen::Vector3d constrainedPoint(const PointConstraint& c, const Eigen::VectorXd& x) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) p += c.weights[i] * x.segment<3>(3 * c.vertices[i]);
  return p;
}

Eigen::SparseMatrix<double> constraintRows(const std::vector<PointConstraint>& constraints,
                                           Eigen::Index vertexCount) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(constraints.size() * 12);
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    const PointConstraint& c = constraints[k];
    const double root = std::sqrt(c.weight);
    for (int i = 0; i < 4; ++i) {
      if (c.weights[i] == 0.0) continue;
      for (int d = 0; d < 3; ++d)
        entries.emplace_back(int(3 * k) + d, 3 * c.vertices[i] + d, root * c.weights[i]);
    }
  }
  Eigen::SparseMatrix<double> A(Eigen::Index(3 * constraints.size()), 3 * vertexCount);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

Eigen::VectorXd constraintResiduals(const std::vector<PointConstraint>& constraints, const Eigen::VectorXd& x) {
  Eigen::VectorXd r(Eigen::Index(3 * constraints.size()));
  for (std::size_t k = 0; k < constraints.size(); ++k)
    r.segment<3>(Eigen::Index(3 * k)) =
        std::sqrt(constraints[k].weight) * (constrainedPoint(constraints[k], x) - constraints[k].target);
  return r;
}

std::vector<PointConstraint> embedMaterialPoints(const MatrixX3d& restV, const MatrixX4i& T,
                                                 const MatrixX3d& points, const MatrixX3d& targets, double c) {
  if (points.rows() != targets.rows())
    throw UsageError("material points and their targets differ in number");
  std::vector<PointConstraint> constraints;
  if (points.rows() == 0) return constraints;
  const TetLocator locator(restV, T);
  const std::vector<TetLocation> where = locator.locateOrNearest(points);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    PointConstraint k;
    k.tet = where[i].tet;
    for (int j = 0; j < 4; ++j) k.vertices[j] = T(where[i].tet, j);
    k.weights = where[i].barycentric;
    k.target = targets.row(i).transpose();
    k.weight = c;
    constraints.push_back(k);
  }
  return constraints;
}

PointSprings asSprings(const std::vector<PointConstraint>& constraints, double k) {
  PointSprings springs;
  springs.targets.resize(Eigen::Index(constraints.size()), 3);
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    springs.points.push_back({constraints[i].tet, constraints[i].weights});
    springs.targets.row(Eigen::Index(i)) = constraints[i].target.transpose();
  }
  springs.stiffness = Eigen::VectorXd::Constant(Eigen::Index(constraints.size()), k);
  return springs;
}

}  // namespace vesalius::fit
