#include "vesalius/fat/erode_skin.h"

#include "vesalius/core/box_tree.h"
#include "vesalius/core/error.h"
#include "vesalius/core/grid_sampling.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/core/triangle_tree.h"

#include <Eigen/LU>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

namespace vesalius::fat {

namespace {

using Index = Eigen::Index;
using Pairs = std::vector<std::pair<int, int>>;

constexpr double kInnerBallRatio = 0.9;  // κ of innerRadius: normals up to 25.8° off are tolerated

// Unique 1-ring neighbours of every vertex, compressed: those of v are list[start[v] .. start[v + 1]).
struct Rings {
  std::vector<Index> start, list;
  Index size(Index v) const { return start[v + 1] - start[v]; }
};

Rings oneRings(Index nv, const MatrixX3i& F) {
  std::vector<std::vector<Index>> nb(nv);
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) nb[F(f, c)].push_back(F(f, (c + 1) % 3)), nb[F(f, (c + 1) % 3)].push_back(F(f, c));
  Rings r;
  r.start.assign(nv + 1, 0);
  for (Index v = 0; v < nv; ++v) {
    std::sort(nb[v].begin(), nb[v].end());
    nb[v].erase(std::unique(nb[v].begin(), nb[v].end()), nb[v].end());
    r.start[v + 1] = r.start[v] + Index(nb[v].size());
    r.list.insert(r.list.end(), nb[v].begin(), nb[v].end());
  }
  return r;
}

// The triangles around every vertex, sorted, in the same compressed form.
Rings vertexFaces(Index nv, const MatrixX3i& F) {
  Rings r;
  r.start.assign(nv + 1, 0);
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++r.start[F(f, c) + 1];
  for (Index v = 0; v < nv; ++v) r.start[v + 1] += r.start[v];
  r.list.resize(r.start[nv]);
  std::vector<Index> next(r.start.begin(), r.start.end() - 1);
  for (Index f = 0; f < F.rows(); ++f)  // in increasing f, so each list comes out sorted
    for (int c = 0; c < 3; ++c) r.list[next[F(f, c)]++] = f;
  return r;
}

// Rows of `D` flagged in `active` replaced `iterations` times by the normalised sum of their own and
// their neighbours' rows (Jacobi, so the vertex order does not matter).
void averageDirections(MatrixX3d& D, const Rings& rings, const std::vector<char>& active, int iterations) {
  for (int it = 0; it < iterations; ++it) {
    MatrixX3d next = D;
    tbb::parallel_for(Index(0), D.rows(), [&](Index v) {
      if (!active[v]) return;
      Eigen::RowVector3d sum = D.row(v);
      for (Index k = rings.start[v]; k < rings.start[v + 1]; ++k) sum += D.row(rings.list[k]);
      const double n = sum.norm();
      if (n > 0) next.row(v) = sum / n;
    });
    D.swap(next);
  }
}

// Inward unit normals: the area-weighted normals of the faces around each vertex, averaged over the 1-ring.
MatrixX3d inwardNormals(const MatrixX3d& V, const MatrixX3i& F, const Rings& rings, int iterations) {
  const double sign = enclosedVolume(V, F) < 0 ? 1.0 : -1.0;  // outward faces: inward is −n
  MatrixX3d N = sign * vertexNormals(V, F);
  std::vector<char> active(V.rows());
  for (Index v = 0; v < V.rows(); ++v) active[v] = rings.size(v) > 0;
  averageDirections(N, rings, active, iterations);
  return N;
}

// For every skin voxel whose tree holds fat, the tree's deepest voxel (ties: the lowest index).
std::unordered_map<std::int32_t, std::int32_t> deepestOfTrees(const FatForest& forest) {
  std::unordered_map<std::int32_t, std::int32_t> deepest;
  const std::vector<std::int32_t>& root = forest.root();
  const std::vector<float>& d = forest.distance();
  for (std::int32_t v = 0; v < std::int32_t(root.size()); ++v) {
    if (root[v] < 0 || root[v] == v) continue;
    const auto [it, inserted] = deepest.try_emplace(root[v], v);
    if (!inserted && d[v] > d[it->second]) it->second = v;
  }
  return deepest;
}

// Direction toward the deepest voxel of the deepest tree rooted within `radius` of p; zero if none.
Eigen::Vector3d pathDirection(const FatForest& forest, const std::unordered_map<std::int32_t, std::int32_t>& deepest,
                              const Eigen::Matrix3d& Minv, const Eigen::Vector3d& p, double radius) {
  const GridGeometry& g = forest.geometry();
  const auto [lo, hi] = indexBoxAroundBall(g, Minv, p, radius);
  const std::int64_t nx = g.size.x(), ny = g.size.y();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) {
        const std::int64_t s = g.linearIndex(i, j, k);
        if (!forest.isSkin(s)) continue;
        const auto it = deepest.find(std::int32_t(s));
        if (it == deepest.end() || (g.indexToWorld(Eigen::Vector3d(i, j, k)) - p).norm() > radius) continue;
        const std::int32_t e = it->second;
        const Eigen::Vector3d end =
            g.indexToWorld(Eigen::Vector3d(double(e % nx), double((e / nx) % ny), double(e / (nx * ny))));
        sum += forest.distance()[e] * (end - p).normalized();
      }
  return sum.squaredNorm() > 0 ? Eigen::Vector3d(sum.normalized()) : sum;
}

// The inward direction of every vertex (ErodeSkin step 1); `source` gets kPath, kNormal or kNone.
MatrixX3d inwardDirections(const MatrixX3d& V, const MatrixX3d& normals, const Rings& rings, const FatForest* forest,
                           const ErodeSkinOptions& o, Eigen::VectorXi& source) {
  const Index nv = V.rows();
  MatrixX3d D = normals;
  source = Eigen::VectorXi::Constant(nv, ErodedSkin::kNormal);
  for (Index v = 0; v < nv; ++v)
    if (normals.row(v).squaredNorm() == 0) source[v] = ErodedSkin::kNone;
  if (!forest) return D;
  const GridGeometry& g = forest->geometry();
  const Eigen::Matrix3d M = g.direction * g.spacing.asDiagonal();
  const double radius = o.pathRadiusMm > 0 ? o.pathRadiusMm : 2 * (M * Eigen::Vector3d::Ones()).norm();
  const Eigen::Matrix3d Minv = M.inverse();
  const auto deepest = deepestOfTrees(*forest);
  std::vector<char> onPath(nv, 0);
  tbb::parallel_for(Index(0), nv, [&](Index v) {
    if (source[v] == ErodedSkin::kNone) return;
    const Eigen::Vector3d d = pathDirection(*forest, deepest, Minv, V.row(v).transpose(), radius);
    if (d.dot(normals.row(v).transpose()) < o.minPathCosine) return;  // also the zero vector: no tree near
    D.row(v) = d.transpose(), source[v] = ErodedSkin::kPath, onPath[v] = 1;
  });
  averageDirections(D, rings, onPath, o.directionSmoothingIterations);
  return D;
}

// r(x) by relaxed ball shrinking (ErodeSkin step 2): the largest s <= r0 for which the ball of radius κs
// centred at c = x + s·n holds no point of the surface but x's own triangles (`around`, sorted). A
// nearest point q with |c − q| < κs rules out the s between the roots of
// (1 − κ²) s² − 2 (n·w) s + |w|² = 0, w = q − x, so s drops to the smaller root (κ = 1 is the exact
// shrinking ball, s = |w|² / (2 n·w)). `tree` holds the triangles' boxes.
double innerRadius(const BoxTree& tree, const MatrixX3d& V, const MatrixX3i& F, const Eigen::Vector3d& x,
                   const Eigen::Vector3d& n, const Index* around, const Index* aroundEnd, double r0) {
  constexpr double kappa = kInnerBallRatio;
  double s = r0;
  for (int it = 0; it < 200 && s > 1e-9 * r0; ++it) {
    const Eigen::Vector3d c = x + s * n;
    double bound = kappa * kappa * s * s * (1 - 1e-9);  // points strictly inside the ball
    Eigen::Vector3d q = c;  // set whenever bound shrinks, which the test below requires
    tree.nearestFirst(c, bound, [&](int f) {
      if (std::binary_search(around, aroundEnd, Index(f))) return;
      Eigen::Vector3d w;
      const Eigen::Vector3d p = closestPointOnTriangle(c, V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2)), w);
      if ((p - c).squaredNorm() < bound) bound = (p - c).squaredNorm(), q = p;
    });
    if (bound >= kappa * kappa * s * s * (1 - 1e-9)) break;  // nothing inside
    const Eigen::Vector3d w = q - x;
    const double b = n.dot(w), a = 1 - kappa * kappa, disc = std::max(0.0, b * b - a * w.squaredNorm());
    const double next = w.squaredNorm() / (b + std::sqrt(disc));  // the smaller root, without cancellation
    if (!(next < s)) break;  // round-off
    s = next;
  }
  return s;
}

// Reductions ρ >= needed, spread over the 1-ring: ρ ← max(needed, mean of the neighbours' ρ).
Eigen::VectorXd spreadReductions(const Eigen::VectorXd& needed, const Rings& rings, int iterations) {
  Eigen::VectorXd rho = needed;
  for (int it = 0; it < iterations; ++it) {
    Eigen::VectorXd next = rho;
    tbb::parallel_for(Index(0), rho.size(), [&](Index v) {
      if (rings.size(v) == 0) return;
      double sum = 0;
      for (Index k = rings.start[v]; k < rings.start[v + 1]; ++k) sum += rho[rings.list[k]];
      next[v] = std::max(needed[v], sum / double(rings.size(v)));
    });
    rho.swap(next);
  }
  return rho;
}

void checkInputs(const MatrixX3d& V, const MatrixX3i& F, const Eigen::VectorXd& t, const ErodeSkinOptions& o) {
  if (t.size() != V.rows())
    throw BadInput(o.source, "thickness has " + std::to_string(t.size()) + " values for " + std::to_string(V.rows()) +
                                 " vertices");
  for (Index v = 0; v < t.size(); ++v) {
    if (!std::isfinite(t[v])) throw BadInput(o.source, "thickness at vertex " + std::to_string(v) + " is not finite");
    if (t[v] < 0) {
      std::ostringstream problem;
      problem << "thickness at vertex " << v << " is negative (" << t[v] << " mm)";
      throw BadInput(o.source, problem.str());
    }
  }
  if (F.rows() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw BadInput(o.source, "a triangle indexes outside the " + std::to_string(V.rows()) + " vertices");
  if (!(o.maxFractionOfInnerRadius > 0 && o.maxFractionOfInnerRadius <= 1) && !std::isinf(o.maxFractionOfInnerRadius))
    throw UsageError("erode skin: maxFractionOfInnerRadius must be in (0, 1] or infinite");
  if (!(o.pathRadiusMm >= 0) || std::isnan(o.minPathCosine) || o.normalSmoothingIterations < 0 ||
      o.directionSmoothingIterations < 0 || o.limitSmoothingIterations < 0 || o.maxRepairRounds < 0)
    throw UsageError("erode skin: radii and iteration counts must be >= 0");
}

// Crossing pairs of `pairs` that are not in `before` (both sorted).
Pairs newPairs(const Pairs& pairs, const Pairs& before) {
  Pairs out;
  std::set_difference(pairs.begin(), pairs.end(), before.begin(), before.end(), std::back_inserter(out));
  return out;
}

// The moves of ErodeSkin steps 3 and 4: thickness less the spread of the needed reductions.
struct Moves {
  const MatrixX3d& V;
  const Eigen::VectorXd& thickness;
  const Rings& rings;
  int spreading;
  Eigen::VectorXd needed;

  // Sets out.displacement and out.V; appends to `changed` the vertices whose move changed.
  void apply(ErodedSkin& out, std::vector<int>* changed) const {
    const Eigen::VectorXd rho = spreadReductions(needed, rings, spreading);
    for (Index v = 0; v < V.rows(); ++v) {
      const double m = std::max(0.0, thickness[v] - rho[v]);
      if (changed && m != out.displacement[v]) changed->push_back(int(v));
      out.displacement[v] = m;
      out.V.row(v) = V.row(v) + m * out.direction.row(v);
    }
  }
};

// ErodeSkin step 4 from the crossing pairs `pairs` of out.V; returns those left. `repaired` flags the
// vertices whose moves were cut.
Pairs repairCrossings(const MatrixX3i& F, const Pairs& before, Pairs pairs, Moves& moves, int maxRounds,
                      ErodedSkin& out, std::vector<char>& repaired) {
  for (Pairs crossing = newPairs(pairs, before); !crossing.empty() && out.repairRounds < maxRounds;
       crossing = newPairs(pairs, before)) {
    const bool last = 4 * ++out.repairRounds > 3 * maxRounds;
    for (const auto& [a, b] : crossing)
      for (int f : {a, b})
        for (int c = 0; c < 3; ++c) {
          const Index v = F(f, c);
          const double t = moves.thickness[v];
          moves.needed[v] = std::max(moves.needed[v], last ? t : t - 0.5 * out.displacement[v]);
          repaired[v] = 1;
        }
    std::vector<int> changed;
    moves.apply(out, &changed);
    // Only triangles around moved vertices can have gained or lost a crossing.
    std::vector<char> isChanged(moves.V.rows(), 0), candidate(F.rows(), 0);
    for (int v : changed) isChanged[v] = 1;
    std::vector<int> faces;
    for (Index f = 0; f < F.rows(); ++f)
      if (isChanged[F(f, 0)] || isChanged[F(f, 1)] || isChanged[F(f, 2)]) faces.push_back(int(f)), candidate[f] = 1;
    Pairs kept;
    for (const auto& p : pairs)
      if (!candidate[p.first] && !candidate[p.second]) kept.push_back(p);
    const Pairs fresh = faces.empty() ? Pairs() : selfIntersections(out.V, F, faces);
    pairs.clear();
    std::merge(kept.begin(), kept.end(), fresh.begin(), fresh.end(), std::back_inserter(pairs));
  }
  return pairs;
}

}  // namespace

ErodedSkin erodeSkin(const MatrixX3d& V, const MatrixX3i& F, const Eigen::VectorXd& thickness, const FatForest* forest,
                     const ErodeSkinOptions& o) {
  checkInputs(V, F, thickness, o);
  const Index nv = V.rows();
  ErodedSkin out;
  out.V = V;
  out.displacement = Eigen::VectorXd::Zero(nv);
  out.innerRadius = Eigen::VectorXd::Zero(nv);
  out.direction = MatrixX3d::Zero(nv, 3);
  out.directionSource = Eigen::VectorXi::Zero(nv);
  if (nv == 0 || F.rows() == 0) return out;

  const Rings rings = oneRings(nv, F);
  const MatrixX3d normals = inwardNormals(V, F, rings, o.normalSmoothingIterations);
  out.direction = inwardDirections(V, normals, rings, forest, o, out.directionSource);

  // r(x) only matters up to t / fraction: larger balls allow the whole move, and small ones are cheap.
  const BoxTree tree(elementBoxes(V, F, "triangle"));
  const Rings faces = vertexFaces(nv, F);
  Eigen::VectorXd needed = Eigen::VectorXd::Zero(nv);
  tbb::parallel_for(Index(0), nv, [&](Index v) {
    if (out.directionSource[v] == ErodedSkin::kNone || thickness[v] == 0 || std::isinf(o.maxFractionOfInnerRadius))
      return;
    const double r0 = thickness[v] / o.maxFractionOfInnerRadius;
    const Index* around = faces.list.data() + faces.start[v];
    out.innerRadius[v] = innerRadius(tree, V, F, V.row(v).transpose(), normals.row(v).transpose(), around,
                                     around + faces.size(v), r0);
    needed[v] = std::max(0.0, thickness[v] - o.maxFractionOfInnerRadius * out.innerRadius[v]);
  });
  out.limited = (needed.array() > 0).count();
  for (Index v = 0; v < nv; ++v)
    if (out.directionSource[v] == ErodedSkin::kNone) needed[v] = thickness[v];  // nowhere to go: stays

  Moves moves{V, thickness, rings, o.limitSmoothingIterations, needed};
  moves.apply(out, nullptr);
  const Pairs before = selfIntersections(V, F);
  std::vector<char> repaired(nv, 0);
  const Pairs pairs =
      repairCrossings(F, before, selfIntersections(out.V, F), moves, o.maxRepairRounds, out, repaired);

  out.selfIntersectionsBefore = long(before.size());
  out.selfIntersectionsAfter = long(pairs.size());
  out.newSelfIntersections = long(newPairs(pairs, before).size());
  for (Index v = 0; v < nv; ++v) {
    const double m = out.displacement[v];
    out.repaired += repaired[v];
    out.reduced += m < thickness[v];
    if (m > 0) (out.directionSource[v] == ErodedSkin::kPath ? out.movedAlongPaths : out.movedAlongNormals) += 1;
  }
  out.maxDisplacement = out.displacement.maxCoeff();
  out.meanDisplacement = out.displacement.mean();
  return out;
}

}  // namespace vesalius::fat
