// Laplacian-regularised displacement towards targets (smooth_displacement.h).
#include "vesalius/fit/smooth_displacement.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/linalg/sparse_cholesky.h"

#include <Eigen/SparseCore>

#include <cmath>
#include <vector>

namespace vesalius::fit {
namespace {

void validate(const TriMesh& surface, const MatrixX3d& points, const MatrixX3d& displacements,
              const Eigen::VectorXd& weights, const SmoothDisplacementOptions& o) {
  if (surface.F.rows() == 0) throw UsageError("smooth displacement: the surface has no triangles");
  if (displacements.rows() != points.rows() || weights.size() != points.rows())
    throw UsageError("smooth displacement: one displacement and one weight per point are needed");
  if (!points.allFinite() || !displacements.allFinite())
    throw UsageError("smooth displacement: points and displacements must be finite");
  if (!(weights.array() >= 0).all() || !weights.allFinite())
    throw UsageError("smooth displacement: weights must be non-negative and finite");
  if (!(o.smoothness > 0) || !std::isfinite(o.smoothness))
    throw UsageError("smooth displacement: smoothness must be positive");
}

}  // namespace

MatrixX3d smoothDisplacement(const TriMesh& surface, const MatrixX3d& points, const MatrixX3d& displacements,
                             const Eigen::VectorXd& weights, const SmoothDisplacementOptions& options) {
  validate(surface, points, displacements, weights, options);
  const Eigen::Index n = surface.V.rows();
  const double total = weights.sum();
  if (!(total > 0)) return MatrixX3d::Zero(n, 3);
  const double lambda = options.smoothness * total / double(n);

  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)  // each interior edge is met twice: weight λ / 2
    for (int c = 0; c < 3; ++c) {
      const int i = surface.F(f, c), j = surface.F(f, (c + 1) % 3);
      entries.insert(entries.end(), {{i, i, lambda / 2}, {j, j, lambda / 2}, {i, j, -lambda / 2}, {j, i, -lambda / 2}});
    }
  for (Eigen::Index i = 0; i < n; ++i) entries.emplace_back(int(i), int(i), 1e-9 * lambda);

  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  const std::vector<ClosestPoint> closest = TriangleTree(surface.V, surface.F).closest(points);
  for (Eigen::Index p = 0; p < points.rows(); ++p) {
    if (weights[p] == 0) continue;
    const ClosestPoint& c = closest[std::size_t(p)];
    for (int a = 0; a < 3; ++a) {
      const int i = surface.F(c.face, a);
      rhs.row(i) += weights[p] * c.barycentric[a] * displacements.row(p);
      for (int b = 0; b < 3; ++b)
        entries.emplace_back(i, surface.F(c.face, b), weights[p] * c.barycentric[a] * c.barycentric[b]);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  SparseCholesky cholesky;
  cholesky.factor(A);
  return cholesky.solve(rhs);
}

}  // namespace vesalius::fit
