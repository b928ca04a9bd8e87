// Evenly spread surface points: area-uniform candidates, farthest-point selection (surface_samples.h).
#include "vesalius/meshing/surface_samples.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

namespace vesalius::meshing {

namespace {

// A double in [0, 1) from the top 53 bits of one 64-bit draw: the same on every platform.
double unitDouble(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1.0p-53; }

Eigen::Vector3d vertex(const TriMesh& m, int f, int c) { return m.V.row(m.F(f, c)).transpose(); }

// Prefix sums of the triangle areas (#F); the last one is the total.
std::vector<double> cumulativeAreas(const TriMesh& m) {
  const Eigen::VectorXd area = triangleAreas(m.V, m.F);
  std::vector<double> cumulative(std::size_t(area.size()));
  std::partial_sum(area.data(), area.data() + area.size(), cumulative.begin());
  return cumulative;
}

MatrixX3d areaUniformPoints(const TriMesh& m, int n, std::uint64_t seed) {
  const std::vector<double> cumulative = cumulativeAreas(m);
  const double total = cumulative.back();
  if (!std::isfinite(total)) throw BadInput("", "surface has non-finite coordinates");
  if (!(total > 0.0)) throw BadInput("", "surface has no area to put points on");
  std::mt19937_64 rng(seed);
  MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double area = unitDouble(rng) * total;
    // The first triangle whose prefix sum exceeds `area`: triangles without area are never chosen.
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), area);
    const int f = int(std::min<std::ptrdiff_t>(it - cumulative.begin(), std::ptrdiff_t(cumulative.size()) - 1));
    const double r = std::sqrt(unitDouble(rng)), v = unitDouble(rng);
    P.row(i) = ((1.0 - r) * vertex(m, f, 0) + r * (1.0 - v) * vertex(m, f, 1) + r * v * vertex(m, f, 2)).transpose();
  }
  return P;
}

}  // namespace

MatrixX3d spreadSurfacePoints(const TriMesh& surface, int count, std::uint64_t seed, const SpreadOptions& options) {
  if (count <= 0) throw UsageError("the number of points must be positive, not " + std::to_string(count));
  if (options.candidates < 0) throw UsageError("the number of candidates must not be negative");
  if (surface.F.rows() == 0) throw BadInput("", "surface has no triangles to put points on");
  const long long automatic = std::min<long long>(std::max(1000LL, 32LL * count), std::numeric_limits<int>::max());
  const int candidates = options.candidates > 0 ? options.candidates : int(automatic);
  if (count > candidates)
    throw UsageError("cannot choose " + std::to_string(count) + " points from " + std::to_string(candidates) +
                     " candidates");
  const Eigen::Matrix3Xd C = areaUniformPoints(surface, candidates, seed).transpose();  // one column a point

  // Farthest-point sampling; `nearest` is each candidate's squared distance to the chosen set.
  std::vector<double> nearest(std::size_t(candidates), std::numeric_limits<double>::infinity());
  MatrixX3d chosen(count, 3);
  int next = 0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d p = C.col(next);
    chosen.row(k) = p.transpose();
    int farthest = 0;
    double farthestDistance = -1.0;
    for (int i = 0; i < candidates; ++i) {
      const double d = (C.col(i) - p).squaredNorm();
      double& n = nearest[std::size_t(i)];
      if (d < n) n = d;
      if (n > farthestDistance) farthestDistance = n, farthest = i;
    }
    next = farthest;
  }
  return chosen;
}

TriMesh withinScan(const TriMesh& surface, const GridGeometry& scan) {
  std::vector<bool> inside(std::size_t(surface.V.rows()));
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v)
    inside[std::size_t(v)] = scan.seesPoint(surface.V.row(v).transpose());
  std::vector<int> keep;
  for (Eigen::Index f = 0; f < surface.F.rows(); ++f)
    if (inside[std::size_t(surface.F(f, 0))] && inside[std::size_t(surface.F(f, 1))] &&
        inside[std::size_t(surface.F(f, 2))])
      keep.push_back(int(f));
  const Eigen::VectorXi rows = Eigen::Map<const Eigen::VectorXi>(keep.data(), Eigen::Index(keep.size()));
  TriMesh result;
  result.V = surface.V;
  result.UV = surface.UV;
  result.vertexAttributes = surface.vertexAttributes;
  result.F = surface.F(rows, Eigen::all);
  if (surface.FUV.rows() == surface.F.rows() && surface.FUV.rows() > 0) result.FUV = surface.FUV(rows, Eigen::all);
  result.faceAttributes = surface.faceAttributes.selectRows(rows);
  return result;
}

}  // namespace vesalius::meshing
