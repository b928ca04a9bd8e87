#include "vesalius/fit/surface_projection.h"

#include "vesalius/fem/plastic_fem.h"

#include "vesalius/core/triangle_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace vesalius::fit {
namespace {

std::array<int, 3> sortedFace(int a, int b, int c) {
  std::array<int, 3> f{a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

}  // namespace

SurfaceProjection::SurfaceProjection(const MatrixX4i& T)
    : T_(T), F_(tetBoundary(T)), faceTet_(std::size_t(F_.rows()), -1) {
  std::map<std::array<int, 3>, int> boundary;
  for (Eigen::Index f = 0; f < F_.rows(); ++f) boundary[sortedFace(F_(f, 0), F_(f, 1), F_(f, 2))] = int(f);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      int c[3], n = 0;
      for (int i = 0; i < 4; ++i)
        if (i != skip) c[n++] = T(t, i);
      const auto it = boundary.find(sortedFace(c[0], c[1], c[2]));
      if (it != boundary.end()) faceTet_[std::size_t(it->second)] = int(t);
    }
}

std::vector<PointConstraint> SurfaceProjection::closestPoints(const Eigen::VectorXd& x, const MatrixX3d& markers,
                                                              double c) const {
  std::vector<PointConstraint> constraints;
  if (markers.rows() == 0) return constraints;
  const TriangleTree tree(PlasticFem::unflatten(x), F_);
  const std::vector<ClosestPoint> hits = tree.closest(markers);
  constraints.reserve(hits.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    PointConstraint k;
    k.tet = faceTet_[std::size_t(hits[i].face)];
    for (int j = 0; j < 4; ++j) {
      k.vertices[j] = T_(k.tet, j);
      for (int f = 0; f < 3; ++f)
        if (F_(hits[i].face, f) == k.vertices[j]) k.weights[j] = hits[i].barycentric[f];
    }
    k.target = markers.row(Eigen::Index(i)).transpose();
    k.weight = c;
    constraints.push_back(k);
  }
  return constraints;
}

Eigen::VectorXd SurfaceProjection::distances(const Eigen::VectorXd& x, const MatrixX3d& markers) const {
  Eigen::VectorXd d(markers.rows());
  if (markers.rows() == 0) return d;
  const TriangleTree tree(PlasticFem::unflatten(x), F_);
  const std::vector<ClosestPoint> hits = tree.closest(markers);
  for (std::size_t i = 0; i < hits.size(); ++i) d[Eigen::Index(i)] = std::sqrt(hits[i].squaredDistance);
  return d;
}

}  // namespace vesalius::fit
