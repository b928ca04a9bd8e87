#include "vesalius/fat/bone_fat_thickness.h"

#include "vesalius/core/error.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

namespace vesalius::fat {

namespace {

using Index = Eigen::Index;

// Row of the weighted voxel centre nearest to world point p, searching cubic shells of growing radius
// around its voxel; after the first hit, the shells that may still hold a nearer centre.
std::int32_t nearestWeightedRow(const BoundedBiharmonicWeights& b, const Eigen::Vector3d& p, const Eigen::Vector3d& index) {
  const GridGeometry& g = b.geometry;
  const Eigen::Vector3i c = index.array().round().cast<int>().matrix();
  const double anisotropy = g.spacing.maxCoeff() / g.spacing.minCoeff();
  std::int32_t best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  int last = g.size.maxCoeff() + std::abs(c.x()) + std::abs(c.y()) + std::abs(c.z());
  for (int r = 0; r <= last; ++r)
    for (int k = c.z() - r; k <= c.z() + r; ++k)
      for (int j = c.y() - r; j <= c.y() + r; ++j)
        for (int i = c.x() - r; i <= c.x() + r; ++i) {
          if (std::max({std::abs(i - c.x()), std::abs(j - c.y()), std::abs(k - c.z())}) != r) continue;
          if (!g.contains(i, j, k)) continue;
          const std::int32_t row = b.row[g.linearIndex(i, j, k)];
          if (row < 0) continue;
          const double d = (g.indexToWorld(Eigen::Vector3d(i, j, k)) - p).norm();
          if (d < bestDistance) {
            if (best < 0) last = std::min(last, int(std::ceil((r + 1) * anisotropy)) + 1);
            best = row, bestDistance = d;
          }
        }
  return best;
}

}  // namespace

BoneFatThickness boneFatThickness(const BoundedBiharmonicWeights& weights, const MatrixX3d& P,
                                  const Eigen::VectorXd& amounts, const BoneFatOptions& options) {
  const Index m = weights.W.cols();
  if (weights.W.rows() == 0) throw UsageError("bone fat thickness: no weights");
  if (amounts.size() != m || !amounts.allFinite())
    throw UsageError("bone fat thickness: " + std::to_string(amounts.size()) + " amounts for " + std::to_string(m) +
                     " bones, or an amount that is not a number");
  if (!std::isfinite(options.maxThicknessMm) || options.maxThicknessMm < 0)
    throw UsageError("bone fat thickness: the maximum thickness must be finite and >= 0");
  BoneFatThickness out;
  out.weights = Eigen::MatrixXd::Zero(P.rows(), m);
  const GridGeometry& g = weights.geometry;
  std::vector<char> nearest(P.rows(), 0);
  tbb::parallel_for(Index(0), P.rows(), [&](Index p) {
    const Eigen::Vector3d x = P.row(p).transpose(), index = g.worldToIndex(x);
    const Eigen::Vector3i lo = index.array().floor().cast<int>().matrix();
    double total = 0;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3i at = lo + Eigen::Vector3i(corner & 1, (corner >> 1) & 1, corner >> 2);
      if (!g.contains(at.x(), at.y(), at.z())) continue;
      const std::int32_t row = weights.row[g.linearIndex(at.x(), at.y(), at.z())];
      if (row < 0) continue;
      double f = 1;
      for (int a = 0; a < 3; ++a) f *= 1 - std::abs(index[a] - at[a]);
      out.weights.row(p) += f * weights.W.row(row);
      total += f;
    }
    if (total > 1e-9) {
      out.weights.row(p) /= total;
    } else {
      out.weights.row(p) = weights.W.row(nearestWeightedRow(weights, x, index));
      nearest[p] = 1;
    }
  });
  for (const char n : nearest) out.fromNearestVoxel += n;
  out.thickness = options.maxThicknessMm * (out.weights * amounts);
  return out;
}

}  // namespace vesalius::fat
