#include "vesalius/fat/thickness_at_vertices.h"

#include "vesalius/core/error.h"
#include "vesalius/core/grid_sampling.h"

#include <Eigen/LU>
#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <vector>

namespace vesalius::fat {

namespace {

using Index = Eigen::Index;

// Largest thickness of the skin voxels within `radius` of `p`, or NaN if there are none.
double largestNearby(const FatForest& forest, const Eigen::Matrix3d& Minv, const Eigen::Vector3d& p, double radius) {
  const GridGeometry& g = forest.geometry();
  const auto [lo, hi] = indexBoxAroundBall(g, Minv, p, radius);
  double best = std::numeric_limits<double>::quiet_NaN();
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) {
        const std::int64_t v = g.linearIndex(i, j, k);
        if (!forest.isSkin(v)) continue;
        if ((g.indexToWorld(Eigen::Vector3d(i, j, k)) - p).norm() > radius) continue;
        const double t = forest.thickness().values[v];
        if (!(best >= t)) best = t;  // NaN-aware max
      }
  return best;
}

std::vector<std::vector<Index>> vertexNeighbours(Index nv, const MatrixX3i& F) {
  std::vector<std::vector<Index>> nb(nv);
  for (Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Index a = F(f, c), b = F(f, (c + 1) % 3);
      nb[a].push_back(b);
      nb[b].push_back(a);
    }
  return nb;
}

// Fills NaN entries frontier by frontier (each from the mean of its known neighbours, all of a frontier
// from the previous state, so the order of vertices does not matter), then smooths the filled ones.
void fillFromNeighbours(Eigen::VectorXd& t, const std::vector<std::vector<Index>>& nb,
                        const std::vector<char>& measured, int smoothing, VertexThickness& out,
                        std::vector<char>& unreached) {
  const Index nv = t.size();
  for (bool changed = true; changed;) {
    changed = false;
    Eigen::VectorXd next = t;
    for (Index v = 0; v < nv; ++v) {
      if (!std::isnan(t[v])) continue;
      double sum = 0;
      int count = 0;
      for (Index w : nb[v])
        if (!std::isnan(t[w])) sum += t[w], ++count;
      if (count) next[v] = sum / count, changed = true, ++out.filled;
    }
    t.swap(next);
  }
  for (int it = 0; it < smoothing; ++it) {
    Eigen::VectorXd next = t;
    for (Index v = 0; v < nv; ++v) {
      if (measured[v] || std::isnan(t[v]) || nb[v].empty()) continue;
      double sum = 0;
      int count = 0;
      for (Index w : nb[v])
        if (!std::isnan(t[w])) sum += t[w], ++count;
      if (count) next[v] = sum / count;
    }
    t.swap(next);
  }
  for (Index v = 0; v < nv; ++v)
    if (std::isnan(t[v])) t[v] = 0, unreached[v] = 1, ++out.unreached;
}

}  // namespace

VertexThickness thicknessAtVertices(const FatForest& forest, const MatrixX3d& V, const MatrixX3i& F,
                                    const VertexThicknessOptions& options) {
  if (!(options.radiusMm >= 0) || options.smoothingIterations < 0)
    throw UsageError("fat thickness at vertices: radius and smoothing iterations must be >= 0");
  const GridGeometry& g = forest.geometry();
  const Eigen::Matrix3d M = g.direction * g.spacing.asDiagonal();
  const double radius = options.radiusMm > 0 ? options.radiusMm : (M * Eigen::Vector3d::Ones()).norm();
  const Eigen::Matrix3d Minv = M.inverse();

  VertexThickness out;
  const Index nv = V.rows();
  out.thickness.resize(nv);
  tbb::parallel_for(Index(0), nv, [&](Index v) {
    out.thickness[v] = largestNearby(forest, Minv, V.row(v).transpose(), radius);
  });
  std::vector<char> measured(nv);
  for (Index v = 0; v < nv; ++v) measured[v] = !std::isnan(out.thickness[v]), out.measured += measured[v];
  out.source = Eigen::VectorXi::Constant(nv, VertexThickness::kMeasured);
  if (out.measured == nv) return out;
  std::vector<char> unreached(nv, 0);
  fillFromNeighbours(out.thickness, vertexNeighbours(nv, F), measured, options.smoothingIterations, out, unreached);
  for (Index v = 0; v < nv; ++v)
    if (!measured[v]) out.source[v] = unreached[v] ? VertexThickness::kUnreached : VertexThickness::kFilled;
  return out;
}

}  // namespace vesalius::fat
