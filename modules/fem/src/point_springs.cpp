#include "vesalius/fem/point_springs.h"

#include "vesalius/core/error.h"

#include <string>

namespace vesalius {
namespace {

void checkSprings(const PointSprings& springs, const MatrixX4i& T, Eigen::Index vertexCount) {
  const auto n = Eigen::Index(springs.points.size());
  if (springs.targets.rows() != n || springs.stiffness.size() != n)
    throw BadInput("", "point springs: " + std::to_string(n) + " points but " +
                           std::to_string(springs.targets.rows()) + " targets and " +
                           std::to_string(springs.stiffness.size()) + " stiffnesses");
  if (!springs.targets.allFinite() || !springs.stiffness.allFinite() ||
      (n > 0 && springs.stiffness.minCoeff() < 0))
    throw BadInput("", "point springs: targets and stiffnesses must be finite, stiffnesses non-negative");
  for (const MaterialPoint& p : springs.points)
    if (p.tet < 0 || p.tet >= T.rows() || !p.barycentric.allFinite() || T.row(p.tet).minCoeff() < 0 ||
        T.row(p.tet).maxCoeff() >= vertexCount)
      throw BadInput("", "point springs: material point in tet " + std::to_string(p.tet) + " of " +
                             std::to_string(T.rows()) + " is not valid");
}

Eigen::Vector3d position(const MaterialPoint& p, const MatrixX4i& T, const Eigen::VectorXd& x) {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  for (int c = 0; c < 4; ++c) y += p.barycentric[c] * x.segment<3>(3 * T(p.tet, c));
  return y;
}

}  // namespace

double pointSpringEnergy(const PointSprings& springs, const MatrixX4i& T, const Eigen::VectorXd& x) {
  checkSprings(springs, T, x.size() / 3);
  double e = 0;
  for (std::size_t i = 0; i < springs.points.size(); ++i) {
    const Eigen::Vector3d r = position(springs.points[i], T, x) - springs.targets.row(Eigen::Index(i)).transpose();
    e += 0.5 * springs.stiffness[Eigen::Index(i)] * r.squaredNorm();
  }
  return e;
}

Eigen::VectorXd pointSpringGradient(const PointSprings& springs, const MatrixX4i& T, const Eigen::VectorXd& x) {
  checkSprings(springs, T, x.size() / 3);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(x.size());
  for (std::size_t i = 0; i < springs.points.size(); ++i) {
    const MaterialPoint& p = springs.points[i];
    const Eigen::Vector3d r = position(p, T, x) - springs.targets.row(Eigen::Index(i)).transpose();
    for (int c = 0; c < 4; ++c)
      g.segment<3>(3 * T(p.tet, c)) += springs.stiffness[Eigen::Index(i)] * p.barycentric[c] * r;
  }
  return g;
}

Eigen::SparseMatrix<double> pointSpringHessian(const PointSprings& springs, const MatrixX4i& T, int vertexCount) {
  checkSprings(springs, T, vertexCount);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(48 * springs.points.size());
  for (std::size_t i = 0; i < springs.points.size(); ++i) {
    const MaterialPoint& p = springs.points[i];
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        for (int k = 0; k < 3; ++k)
          entries.emplace_back(3 * T(p.tet, a) + k, 3 * T(p.tet, b) + k,
                               springs.stiffness[Eigen::Index(i)] * p.barycentric[a] * p.barycentric[b]);
  }
  Eigen::SparseMatrix<double> H(3 * vertexCount, 3 * vertexCount);
  H.setFromTriplets(entries.begin(), entries.end());
  return H;
}

}  // namespace vesalius
