// Self-intersections of a triangle surface (see the header for the method and its conventions).
#include "vesalius/core/self_intersections.h"

#include "vesalius/core/box_tree.h"
#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

namespace vesalius {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

// Six times the signed volume of (a, b, c, d): positive when d lies on the side of abc its normal
// (b - a) × (c - a) points away from.
double orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  return (a - d).dot((b - d).cross(c - d));
}

double orient2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  const Vec2 u = b - a, v = c - a;
  return u.x() * v.y() - u.y() * v.x();
}

bool opposite(double x, double y) { return (x > 0 && y < 0) || (x < 0 && y > 0); }

// r on the closed segment pq, given that the three are collinear.
bool onSegment2d(const Vec2& p, const Vec2& q, const Vec2& r) {
  return r.x() >= std::min(p.x(), q.x()) && r.x() <= std::max(p.x(), q.x()) && r.y() >= std::min(p.y(), q.y()) &&
         r.y() <= std::max(p.y(), q.y());
}

bool segmentsIntersect2d(const Vec2& p, const Vec2& q, const Vec2& r, const Vec2& s) {
  const double o1 = orient2d(p, q, r), o2 = orient2d(p, q, s), o3 = orient2d(r, s, p), o4 = orient2d(r, s, q);
  if (opposite(o1, o2) && opposite(o3, o4)) return true;
  return (o1 == 0 && onSegment2d(p, q, r)) || (o2 == 0 && onSegment2d(p, q, s)) ||
         (o3 == 0 && onSegment2d(r, s, p)) || (o4 == 0 && onSegment2d(r, s, q));
}

bool insideTriangle2d(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  const double d1 = orient2d(a, b, p), d2 = orient2d(b, c, p), d3 = orient2d(c, a, p);
  const bool negative = d1 < 0 || d2 < 0 || d3 < 0, positive = d1 > 0 || d2 > 0 || d3 > 0;
  return !(negative && positive);
}

// Segment pq and triangle abc in one plane: compared in the coordinate plane the triangle's normal is
// closest to, where the projection keeps every incidence.
bool coplanarSegmentTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  Eigen::Index axis;
  (b - a).cross(c - a).cwiseAbs().maxCoeff(&axis);
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  auto flat = [&](const Vec3& x) { return Vec2(x(i), x(j)); };
  const Vec2 p2 = flat(p), q2 = flat(q), a2 = flat(a), b2 = flat(b), c2 = flat(c);
  return insideTriangle2d(p2, a2, b2, c2) || insideTriangle2d(q2, a2, b2, c2) ||
         segmentsIntersect2d(p2, q2, a2, b2) || segmentsIntersect2d(p2, q2, b2, c2) ||
         segmentsIntersect2d(p2, q2, c2, a2);
}

bool segmentMeetsTriangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double op = orient3d(a, b, c, p), oq = orient3d(a, b, c, q);
  if ((op > 0 && oq > 0) || (op < 0 && oq < 0)) return false;
  if (op == 0 && oq == 0) return coplanarSegmentTriangle(p, q, a, b, c);
  // pq crosses the plane: it meets the triangle iff the line pq passes inside all three edges.
  const double s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  return (s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0);
}

// Triangles (u, v, a) and (u, v, b) sharing the edge uv overlap only when folded onto each other.
bool foldedOnto(const Vec3& u, const Vec3& v, const Vec3& a, const Vec3& b) {
  const Vec3 e = v - u, da = a - u, db = b - u;
  const double scale = e.norm() * da.norm() * db.norm();
  if (std::abs(e.dot(da.cross(db))) > 1e-12 * scale) return false;
  const Vec3 pa = da - e * (e.dot(da) / e.squaredNorm()), pb = db - e * (e.dot(db) / e.squaredNorm());
  return pa.dot(pb) > 0;
}

class PairTest {
 public:
  PairTest(const MatrixX3d& V, const MatrixX3i& F) : V_(V), F_(F) {}

  bool operator()(int f, int g) const {
    return meshTrianglesMeet({F_(f, 0), F_(f, 1), F_(f, 2)}, {p(F_(f, 0)), p(F_(f, 1)), p(F_(f, 2))},
                             {F_(g, 0), F_(g, 1), F_(g, 2)}, {p(F_(g, 0)), p(F_(g, 1)), p(F_(g, 2))});
  }

 private:
  Vec3 p(int v) const { return V_.row(v).transpose(); }
  const MatrixX3d& V_;
  const MatrixX3i& F_;
};

}  // namespace

bool meshTrianglesMeet(std::array<int, 3> a, std::array<Vec3, 3> pa, std::array<int, 3> b, std::array<Vec3, 3> pb) {
  // Put the shared vertices first in both triangles, in the same order.
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = shared; j < 3; ++j)
      if (a[std::size_t(i)] == b[std::size_t(j)]) {
        std::swap(a[std::size_t(i)], a[std::size_t(shared)]);
        std::swap(pa[std::size_t(i)], pa[std::size_t(shared)]);
        std::swap(b[std::size_t(j)], b[std::size_t(shared)]);
        std::swap(pb[std::size_t(j)], pb[std::size_t(shared)]);
        ++shared;
        break;
      }
  if (shared == 3) return true;
  if (shared == 2) return foldedOnto(pa[0], pa[1], pa[2], pb[2]);
  if (shared == 1)
    return segmentMeetsTriangle(pa[1], pa[2], pb[0], pb[1], pb[2]) ||
           segmentMeetsTriangle(pb[1], pb[2], pa[0], pa[1], pa[2]);
  return trianglesIntersect(pa[0], pa[1], pa[2], pb[0], pb[1], pb[2]);
}

bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                        const Vec3& b2) {
  return segmentMeetsTriangle(a0, a1, b0, b1, b2) || segmentMeetsTriangle(a1, a2, b0, b1, b2) ||
         segmentMeetsTriangle(a2, a0, b0, b1, b2) || segmentMeetsTriangle(b0, b1, a0, a1, a2) ||
         segmentMeetsTriangle(b1, b2, a0, a1, a2) || segmentMeetsTriangle(b2, b0, a0, a1, a2);
}

namespace {

// The pairs with at least one triangle in `candidates`; `all` says that every triangle is one, so each
// pair is tested once (from its smaller index) without a lookup.
std::vector<std::pair<int, int>> crossingPairs(const MatrixX3d& V, const MatrixX3i& F,
                                               const std::vector<int>& candidates, bool all) {
  const std::vector<Eigen::AlignedBox3d> boxes = elementBoxes(V, F, "self-intersection test: a triangle");
  if (boxes.empty() || candidates.empty()) return {};
  std::vector<char> isCandidate(all ? 0 : boxes.size(), 0);
  for (int f : candidates) {
    if (f < 0 || f >= int(boxes.size()))
      throw UsageError("self-intersection test: candidate triangle " + std::to_string(f) + " is not in the mesh");
    if (!all) isCandidate[std::size_t(f)] = 1;
  }
  const BoxTree tree(boxes);
  const PairTest intersect(V, F);
  tbb::combinable<std::vector<std::pair<int, int>>> found;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& range) {
    auto& local = found.local();
    for (std::size_t c = range.begin(); c < range.end(); ++c) {
      const int f = candidates[c];
      // Every box overlapping box f lies within its half diagonal of its centre.
      const double radius2 = 0.25 * boxes[f].diagonal().squaredNorm();
      tree.near(boxes[f].center(), radius2, [&](int g) {
        const bool bothCandidates = all || isCandidate[std::size_t(g)];
        if (g != f && (!bothCandidates || g > f) && boxes[f].intersects(boxes[g]) && intersect(f, g))
          local.emplace_back(std::min(f, g), std::max(f, g));
        return false;
      });
    }
  });
  std::vector<std::pair<int, int>> pairs;
  found.combine_each([&](const auto& local) { pairs.insert(pairs.end(), local.begin(), local.end()); });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

std::vector<std::pair<int, int>> selfIntersections(const MatrixX3d& V, const MatrixX3i& F) {
  std::vector<int> every(std::size_t(F.rows()));
  std::iota(every.begin(), every.end(), 0);
  return crossingPairs(V, F, every, true);
}

std::vector<std::pair<int, int>> selfIntersections(const MatrixX3d& V, const MatrixX3i& F,
                                                   const std::vector<int>& candidates) {
  return crossingPairs(V, F, candidates, false);
}

}  // namespace vesalius
