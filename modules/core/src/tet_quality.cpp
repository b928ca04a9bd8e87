// Quality measures of tetrahedra (see the header).
#include "vesalius/core/tet_quality.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesalius {
namespace {

using Vec3 = Eigen::Vector3d;

// The six edges (i, j) of a tet and, for each, the two other vertices (k, l).
constexpr int kEdges[6][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}, {1, 2, 0, 3}, {1, 3, 0, 2}, {2, 3, 0, 1}};

// Interior dihedral angle at edge pi-pj: the angle between pk and pl seen along the edge, i.e. between
// their components perpendicular to it. atan2 keeps it accurate near 0° and 180°.
double dihedralAngle(const Vec3& pi, const Vec3& pj, const Vec3& pk, const Vec3& pl) {
  const Vec3 e = (pj - pi).normalized();
  const Vec3 u = (pk - pi) - e * e.dot(pk - pi), w = (pl - pi) - e * e.dot(pl - pi);
  return std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / M_PI;
}

// Circumradius from the circumcentre's offset from p0 (Shewchuk's formula with a = p1-p0, ...).
double circumradius(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double det = 2.0 * a.dot(b.cross(c));
  if (det == 0.0) return std::numeric_limits<double>::infinity();
  const Vec3 offset = (a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b)) / det;
  return offset.norm();
}

double longestEdge(const std::array<Vec3, 4>& p) {
  double longest = 0;
  for (const auto& e : kEdges) longest = std::max(longest, (p[e[1]] - p[e[0]]).norm());
  return longest;
}

std::array<Vec3, 4> corners(const MatrixX3d& V, const MatrixX4i& T, Eigen::Index t) {
  return {V.row(T(t, 0)).transpose(), V.row(T(t, 1)).transpose(), V.row(T(t, 2)).transpose(),
          V.row(T(t, 3)).transpose()};
}

}  // namespace

TetQuality tetQuality(const MatrixX3d& V, const MatrixX4i& T) {
  TetQuality q;
  const Eigen::Index n = T.rows();
  q.volume = tetVolumes(V, T);
  q.minDihedral.resize(n);
  q.maxDihedral.resize(n);
  q.radiusEdge.resize(n);
  q.dihedral.resize(n, 6);
  for (Eigen::Index t = 0; t < n; ++t) {
    const auto p = corners(V, T, t);
    double shortest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 6; ++k) {
      const int* e = kEdges[k];
      q.dihedral(t, k) = dihedralAngle(p[e[0]], p[e[1]], p[e[2]], p[e[3]]);
      shortest = std::min(shortest, (p[e[1]] - p[e[0]]).norm());
    }
    q.minDihedral(t) = q.dihedral.row(t).minCoeff();
    q.maxDihedral(t) = q.dihedral.row(t).maxCoeff();
    q.radiusEdge(t) = circumradius(p[1] - p[0], p[2] - p[0], p[3] - p[0]) / shortest;
  }
  return q;
}

TetQualityReport tetQualityReport(const MatrixX3d& V, const MatrixX4i& T) {
  TetQualityReport r;
  r.tets = long(T.rows());
  if (T.rows() == 0) return r;
  const TetQuality q = tetQuality(V, T);
  r.minDihedral = q.minDihedral.minCoeff();
  r.maxDihedral = q.maxDihedral.maxCoeff();
  for (Eigen::Index i = 0; i < q.dihedral.size(); ++i)
    ++r.dihedralHistogram[std::min<std::size_t>(std::size_t(q.dihedral.data()[i] / 10.0), 17)];
  r.maxRadiusEdge = q.radiusEdge.maxCoeff();
  r.meanRadiusEdge = q.radiusEdge.mean();
  r.minVolume = q.volume.minCoeff();
  r.maxVolume = q.volume.maxCoeff();
  r.totalVolume = q.volume.sum();
  for (Eigen::Index t = 0; t < T.rows(); ++t) {
    const double edge = longestEdge(corners(V, T, t));
    if (std::abs(q.volume(t)) <= 1e-12 * edge * edge * edge)
      ++r.degenerate;
    else if (q.volume(t) < 0)
      ++r.inverted;
  }
  return r;
}

}  // namespace vesalius
