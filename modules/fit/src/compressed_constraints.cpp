#include "vesalius/fit/compressed_constraints.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <unordered_map>

namespace vesalius::fit {

CompressedConstraints compressConstraints(const std::vector<PointConstraint>& constraints, Eigen::Index vertexCount) {
  CompressedConstraints out;
  out.rows.resize(0, 3 * vertexCount);
  if (constraints.empty()) return out;
  // The vertices involved, numbered in order of appearance.
  std::unordered_map<int, Eigen::Index> local;
  std::vector<int> vertices;
  for (const PointConstraint& c : constraints)
    for (int i = 0; i < 4; ++i)
      if (c.weights[i] != 0.0 && local.emplace(c.vertices[i], Eigen::Index(vertices.size())).second)
        vertices.push_back(c.vertices[i]);
  const Eigen::Index m = Eigen::Index(vertices.size()), n = Eigen::Index(constraints.size());
  if (m >= n) {  // no fewer rows to gain: the constraints' own rows
    out.rows = constraintRows(constraints, vertexCount);
    out.targets.resize(3 * n);
    for (Eigen::Index k = 0; k < n; ++k)
      out.targets.segment<3>(3 * k) = std::sqrt(constraints[std::size_t(k)].weight) * constraints[std::size_t(k)].target;
    return out;
  }
  // W: #A by #m barycentric weights scaled by √c, so that M = WᵀW and the scaled targets are √c t.
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, m), t(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    const PointConstraint& c = constraints[std::size_t(k)];
    const double root = std::sqrt(c.weight);
    for (int i = 0; i < 4; ++i)
      if (c.weights[i] != 0.0) W(k, local.at(c.vertices[i])) += root * c.weights[i];
    t.row(k) = root * c.target.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(W.transpose() * W);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  Eigen::Index first = 0;
  while (first < m && !(lambda[first] > 1e-12 * lambda[m - 1])) ++first;
  const Eigen::Index r = m - first;
  const Eigen::MatrixXd U = eigen.eigenvectors().rightCols(r);
  const Eigen::VectorXd root = lambda.tail(r).cwiseSqrt();
  const Eigen::MatrixXd Rv = root.asDiagonal() * U.transpose();                                  // r by #m
  const Eigen::MatrixXd q = root.cwiseInverse().asDiagonal() * (U.transpose() * (W.transpose() * t));  // r by 3
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(std::size_t(3 * r * m));
  for (Eigen::Index j = 0; j < r; ++j)
    for (Eigen::Index v = 0; v < m; ++v)
      for (int d = 0; d < 3; ++d) entries.emplace_back(int(3 * j + d), 3 * vertices[std::size_t(v)] + d, Rv(j, v));
  out.rows.resize(3 * r, 3 * vertexCount);
  out.rows.setFromTriplets(entries.begin(), entries.end());
  out.targets = Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(q.transpose()).data(), 3 * r);
  out.offset = 0.5 * (t.squaredNorm() - q.squaredNorm());
  return out;
}

}  // namespace vesalius::fit
