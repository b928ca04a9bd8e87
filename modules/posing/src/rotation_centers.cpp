// Centres of rotation for CoR skinning (rotation_centers.h, Le & Hodgins 2016 eq. 3, seed 001 eqs. 6-7).
#include "vesalius/posing/rotation_centers.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

namespace vesalius::posing {
namespace {

using Eigen::Index;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr double kPairCutoff = 1e-6;     // bone pairs below this fraction of the vertex's largest product
constexpr double kMaxExponent = 50.0;    // exp(-50) ≈ 2e-22: the pair contributes nothing
constexpr double kNoCentre = 1e-12;      // Σ s V below this fraction of the mesh volume: one-bone vertex

// Volume-weighted pieces of eq. 7: per piece (a tet or a group of tets) its weights, volume and moment.
// For a group, `spread` is the covariance of its tets' weights and centroids, Σ_t V_t (w_t - w̄)(c_t - c̄)ᵀ,
// #B by 3 stored in one row-major row of 3#B; with it, the group's share of the numerator of eq. 7 is
// right to first order in the spread of weights within the group: Σ_t s(w_t) V_t c_t ≈ s(w̄) Σ_t V_t c_t +
// ∇s(w̄)ᵀ spread. (Its share of the denominator, Σ_t s(w_t) V_t ≈ s(w̄) Σ_t V_t, has no first-order term:
// w̄ is the mean.) Without it, tets of one group whose small weights fall towards one side of the group
// would all count at its mean, which moves the centres of vertices that follow one bone almost alone.
struct Pieces {
  RowMajorMatrix weights;  // #pieces by #B: w̄
  Eigen::VectorXd volume;  // #pieces
  MatrixX3d moment;        // #pieces by 3: Σ V_t c_t
  RowMajorMatrix spread;   // #pieces by 3#B, or empty for single tets
};

void checkInputs(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W, const RotationCenterOptions& o) {
  if (W.rows() != V.rows())
    throw UsageError("rotation centres: " + std::to_string(W.rows()) + " weight rows for " +
                     std::to_string(V.rows()) + " vertices");
  if (!(o.sigma > 0.0)) throw UsageError("rotation centres: sigma must be positive");
  if (!(o.clusterWidth >= 1e-4 && o.clusterWidth <= 1.0))  // cell indices are 16-bit
    throw UsageError("rotation centres: clusterWidth must be in [1e-4, 1]");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw BadInput("", "rotation centres: a tet refers to a vertex that does not exist");
}

Pieces tetPieces(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W) {
  Pieces p{RowMajorMatrix(T.rows(), W.cols()), tetVolumes(V, T).cwiseAbs(), MatrixX3d(T.rows(), 3), {}};
  tbb::parallel_for(Index(0), T.rows(), [&](Index t) {
    p.weights.row(t) = 0.25 * (W.row(T(t, 0)) + W.row(T(t, 1)) + W.row(T(t, 2)) + W.row(T(t, 3)));
    p.moment.row(t) = p.volume[t] * 0.25 * (V.row(T(t, 0)) + V.row(T(t, 1)) + V.row(T(t, 2)) + V.row(T(t, 3)));
  });
  return p;
}

// Groups tets whose weights fall in the same cell of width h; each group sits at its mean weight.
Pieces groupPieces(const Pieces& tets, double h) {
  const Index n = tets.weights.rows(), bones = tets.weights.cols();
  std::vector<std::uint16_t> keys(std::size_t(n * bones));
  tbb::parallel_for(Index(0), n, [&](Index t) {
    for (Index j = 0; j < bones; ++j)
      keys[std::size_t(t * bones + j)] = std::uint16_t(std::lround(std::clamp(tets.weights(t, j), 0.0, 1.0) / h));
  });
  const std::size_t keyBytes = std::size_t(bones) * sizeof(std::uint16_t);
  const auto key = [&](Index t) { return keys.data() + t * bones; };
  std::vector<Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Index(0));
  // Any total order serves to bring equal keys together; the index breaks ties so the result is deterministic.
  tbb::parallel_sort(order.begin(), order.end(), [&](Index a, Index b) {
    const int c = std::memcmp(key(a), key(b), keyBytes);
    return c < 0 || (c == 0 && a < b);
  });
  std::vector<Index> starts;
  for (Index i = 0; i < n; ++i)
    if (i == 0 || std::memcmp(key(order[std::size_t(i)]), key(order[std::size_t(i - 1)]), keyBytes) != 0) starts.push_back(i);
  starts.push_back(n);
  const Index groups = Index(starts.size()) - 1;
  Pieces g{RowMajorMatrix::Zero(groups, bones), Eigen::VectorXd::Zero(groups), MatrixX3d::Zero(groups, 3),
           RowMajorMatrix::Zero(groups, 3 * bones)};
  tbb::parallel_for(Index(0), groups, [&](Index c) {
    const Index begin = starts[std::size_t(c)], end = starts[std::size_t(c + 1)];
    for (Index i = begin; i < end; ++i) {
      const Index t = order[std::size_t(i)];
      g.volume[c] += tets.volume[t];
      g.moment.row(c) += tets.moment.row(t);
      g.weights.row(c) += tets.volume[t] * tets.weights.row(t);
    }
    if (!(g.volume[c] > 0.0)) return;
    g.weights.row(c) /= g.volume[c];
    const Eigen::RowVector3d centroid = g.moment.row(c) / g.volume[c];
    Eigen::Map<RowMajorMatrix> spread(g.spread.row(c).data(), bones, 3);
    for (Index i = begin; i < end; ++i) {
      const Index t = order[std::size_t(i)];
      const Eigen::RowVector3d offset = tets.moment.row(t) - tets.volume[t] * centroid;  // V_t (c_t - c̄)
      spread += (tets.weights.row(t) - g.weights.row(c)).transpose() * offset;
    }
  });
  return g;
}

struct Pair {
  Index j, k;
  double wj, wk;
};

// The bone pairs of weight row w that matter (see kPairCutoff), into `pairs`.
void activePairs(const Eigen::Ref<const Eigen::RowVectorXd>& w, std::vector<Pair>& pairs) {
  pairs.clear();
  double largest = 0.0;
  for (Index j = 0; j < w.size(); ++j)
    for (Index k = j + 1; k < w.size(); ++k) largest = std::max(largest, w[j] * w[k]);
  if (largest <= 0.0) return;
  for (Index j = 0; j < w.size(); ++j)
    for (Index k = j + 1; k < w.size(); ++k)
      if (w[j] * w[k] >= kPairCutoff * largest) pairs.push_back({j, k, w[j], w[k]});
}

// s(w_p, b) of eq. 6 over the given pairs of w_p, for b a row of #B weights. With `spread` (a row of
// Pieces::spread), adds ∇_b s · spread to `moment`; the pairs' derivatives are, with e the exponential and
// d = w_pj b_k - w_pk b_j, ∂/∂b_j = w_pj w_pk e b_k (1 + 2 d w_pk b_j / σ²) and
// ∂/∂b_k = w_pj w_pk e b_j (1 - 2 d w_pj b_k / σ²).
double similarity(const std::vector<Pair>& pairs, const double* b, const double* spread, double inverseSigma2,
                  Eigen::RowVector3d& moment) {
  double s = 0.0;
  for (const Pair& p : pairs) {
    const double bj = b[p.j], bk = b[p.k], d = p.wj * bk - p.wk * bj, x = d * d * inverseSigma2;
    if (x >= kMaxExponent) continue;
    const double ae = p.wj * p.wk * std::exp(-x);
    s += ae * bj * bk;
    if (!spread) continue;
    const double dj = ae * bk * (1.0 + 2.0 * d * p.wk * bj * inverseSigma2);
    const double dk = ae * bj * (1.0 - 2.0 * d * p.wj * bk * inverseSigma2);
    moment += dj * Eigen::Map<const Eigen::RowVector3d>(spread + 3 * p.j) +
              dk * Eigen::Map<const Eigen::RowVector3d>(spread + 3 * p.k);
  }
  return s;
}

// Eq. 7 for the vertices `rows` against the given pieces: #rows by 3.
MatrixX3d centresFromPieces(const MatrixX3d& V, const Eigen::MatrixXd& W, const Pieces& pieces, double sigma,
                            const Eigen::VectorXi& rows) {
  const double inverseSigma2 = 1.0 / (sigma * sigma), noCentre = kNoCentre * pieces.volume.sum();
  const bool spread = pieces.spread.size() > 0;
  MatrixX3d centres(rows.size(), 3);
  tbb::parallel_for(tbb::blocked_range<Index>(0, rows.size(), 16), [&](const tbb::blocked_range<Index>& r) {
    std::vector<Pair> pairs;
    for (Index row = r.begin(); row < r.end(); ++row) {
      const Index i = rows[row];
      activePairs(W.row(i), pairs);
      double denominator = 0.0;
      Eigen::RowVector3d numerator = Eigen::RowVector3d::Zero();
      if (!pairs.empty())
        for (Index c = 0; c < pieces.volume.size(); ++c) {
          const double s = similarity(pairs, pieces.weights.row(c).data(), spread ? pieces.spread.row(c).data() : nullptr,
                                      inverseSigma2, numerator);
          denominator += s * pieces.volume[c];
          numerator += s * pieces.moment.row(c);
        }
      centres.row(row) = denominator > noCentre ? Eigen::RowVector3d(numerator / denominator) : Eigen::RowVector3d(V.row(i));
    }
  });
  return centres;
}

}  // namespace

MatrixX3d computeRotationCenters(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W,
                                 const RotationCenterOptions& options) {
  checkInputs(V, T, W, options);
  return centresFromPieces(V, W, groupPieces(tetPieces(V, T, W), options.clusterWidth), options.sigma,
                           Eigen::VectorXi::LinSpaced(V.rows(), 0, int(V.rows()) - 1));
}

MatrixX3d computeRotationCentersBruteForce(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W,
                                           const RotationCenterOptions& options, const Eigen::VectorXi& only) {
  checkInputs(V, T, W, options);
  if (only.size() > 0 && (only.minCoeff() < 0 || only.maxCoeff() >= V.rows()))
    throw UsageError("rotation centres: a vertex index to evaluate is out of range");
  const Eigen::VectorXi all = Eigen::VectorXi::LinSpaced(V.rows(), 0, int(V.rows()) - 1);
  return centresFromPieces(V, W, tetPieces(V, T, W), options.sigma, only.size() > 0 ? only : all);
}

}  // namespace vesalius::posing
