// Closest point on a triangle mesh.
//
// A query walks the triangles' BoxTree nearest-first and skips every box farther away than the best
// triangle found so far. The triangle test is Ericson, "Real-Time
// Collision Detection" (2005), §5.1.5, extended to return barycentric weights.
#include "vesalius/core/triangle_tree.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

namespace vesalius {
namespace {

Eigen::Vector3d closestOnSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, double& t) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

// A triangle with no area: the nearest of its three edges (the Voronoi regions of §5.1.5 collapse).
Eigen::Vector3d closestOnDegenerate(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                    Eigen::Vector3d& bary) {
  double tab, tbc, tca;
  const Eigen::Vector3d qab = closestOnSegment(p, a, b, tab);
  const Eigen::Vector3d qbc = closestOnSegment(p, b, c, tbc);
  const Eigen::Vector3d qca = closestOnSegment(p, c, a, tca);
  const double dab = (p - qab).squaredNorm(), dbc = (p - qbc).squaredNorm(),
               dca = (p - qca).squaredNorm();
  if (dab <= dbc && dab <= dca) {
    bary = {1.0 - tab, tab, 0.0};
    return qab;
  }
  if (dbc <= dca) {
    bary = {0.0, 1.0 - tbc, tbc};
    return qbc;
  }
  bary = {tca, 0.0, 1.0 - tca};
  return qca;
}

std::vector<Eigen::AlignedBox3d> triangleBoxes(const MatrixX3d& V, const MatrixX3i& F) {
  if (F.rows() == 0) throw BadInput("", "closest-point tree: the mesh has no triangles");
  return elementBoxes(V, F, "closest-point tree: a triangle");
}

}  // namespace

Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                       Eigen::Vector3d& barycentric) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) {
    barycentric = {1.0, 0.0, 0.0};
    return a;
  }
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) {
    barycentric = {0.0, 1.0, 0.0};
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    barycentric = {1.0 - v, v, 0.0};
    return a + v * ab;
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) {
    barycentric = {0.0, 0.0, 1.0};
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    barycentric = {1.0 - w, 0.0, w};
    return a + w * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    barycentric = {0.0, 1.0 - w, w};
    return b + w * (c - b);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return closestOnDegenerate(p, a, b, c, barycentric);
  const double v = vb / sum, w = vc / sum;
  barycentric = {1.0 - v - w, v, w};
  return a + v * ab + w * ac;
}

TriangleTree::TriangleTree(const MatrixX3d& V, const MatrixX3i& F)
    : V_(V), F_(F), tree_(triangleBoxes(V, F)) {}

ClosestPoint TriangleTree::closest(const Eigen::Vector3d& p) const {
  ClosestPoint best;
  best.squaredDistance = std::numeric_limits<double>::infinity();
  tree_.nearestFirst(p, best.squaredDistance, [&](int f) {
    Eigen::Vector3d bary;
    const Eigen::Vector3d q = closestPointOnTriangle(p, V_.row(F_(f, 0)).transpose(), V_.row(F_(f, 1)).transpose(),
                                                     V_.row(F_(f, 2)).transpose(), bary);
    const double d = (p - q).squaredNorm();
    if (d < best.squaredDistance) best = {q, f, bary, d};
  });
  return best;
}

std::vector<ClosestPoint> TriangleTree::closest(const MatrixX3d& P) const {
  std::vector<ClosestPoint> result(P.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, P.rows(), 256),
                    [&](const tbb::blocked_range<Eigen::Index>& range) {
                      for (Eigen::Index i = range.begin(); i != range.end(); ++i)
                        result[i] = closest(Eigen::Vector3d(P.row(i).transpose()));
                    });
  return result;
}

}  // namespace vesalius
