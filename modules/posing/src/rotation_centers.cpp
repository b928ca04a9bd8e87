// Centres of rotation for CoR skinning (rotation_centers.h, Le & Hodgins 2016 eq. 3; Sujar et al. 2018, eqs. 6-7).
#include "vesalius/posing/rotation_centers.h"

#include "vesalius/core/error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace vesalius::posing {
namespace {

using Eigen::Index;
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

constexpr double kPairCutoff = 1e-6;   // bone pairs below this fraction of the vertex's largest product
constexpr double kMaxExponent = 50.0;  // exp(-50) ≈ 2e-22: the pair contributes nothing
constexpr double kNoCentre = 1e-12;    // Σ s V below this fraction of the mesh volume: one-bone vertex

void checkInputs(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W, const RotationCenterOptions& o) {
  if (W.rows() != V.rows())
    throw UsageError("rotation centres: " + std::to_string(W.rows()) + " weight rows for " +
                     std::to_string(V.rows()) + " vertices");
  if (!(o.sigma > 0.0)) throw UsageError("rotation centres: sigma must be positive");
  if (!(o.clusterWidth >= 1.0 / 1024 && o.clusterWidth <= 1.0))  // a pair's cell table is (1/h + 1)² entries
    throw UsageError("rotation centres: clusterWidth must be in [1/1024, 1]");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= V.rows()))
    throw BadInput("", "rotation centres: a tet refers to a vertex that does not exist");
}

// Per tet: w_t (mean of its corners' weights, #T by #B; by column, so that a bone pair's pass over the tets
// reads two contiguous columns), V_t and c_t.
struct Tets {
  Eigen::MatrixXd weights;
  Eigen::VectorXd volume;
  MatrixX3d centroid;
};

Tets tetWeights(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W) {
  Tets t{Eigen::MatrixXd(T.rows(), W.cols()), tetVolumes(V, T).cwiseAbs(), MatrixX3d(T.rows(), 3)};
  tbb::parallel_for(Index(0), T.rows(), [&](Index i) {
    t.weights.row(i) = 0.25 * (W.row(T(i, 0)) + W.row(T(i, 1)) + W.row(T(i, 2)) + W.row(T(i, 3)));
    t.centroid.row(i) = 0.25 * (V.row(T(i, 0)) + V.row(T(i, 1)) + V.row(T(i, 2)) + V.row(T(i, 3)));
  });
  return t;
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

Index pairIndex(Index j, Index k, Index bones) { return j * bones + k; }

// The tets of one bone pair (j, k) grouped by b_t = (w_tj, w_tk), snapped to cells of width h. With u_t =
// V_t w_tj w_tk, a group stores its mass Σ u_t, moment Σ u_t c_t, u-weighted mean b̄, spread
// Σ u_t (b_t - b̄)(c_t - c̄)ᵀ (2 by 3, row-major) and variance Σ u_t (b_t - b̄)(b_t - b̄)ᵀ (jj, jk, kk). A
// vertex's eq. 6 term for the pair over the group's tets is w_pj w_pk Σ u_t E(d_t) [1, c_t], with the kernel
// E(d) = exp(-d²/σ²) of d_t = w_pj w_tk - w_pk w_tj; Taylor expanded about b̄ (d̄ = d(b̄)) it is
//   w_pj w_pk (E(d̄) Σ u_t [1, c_t] + E'(d̄) [0, ∇dᵀ spread] + ½ E''(d̄) ∇dᵀ variance ∇d [1, c̄]),
// exact in the factor w_tj w_tk (u carries it), with no first-order term in the denominator (b̄ is u's
// mean), and dropping the third order in b_t - b̄ and the second order's correlation with c_t.
struct PairGroups {
  std::vector<double> mass;      // #groups
  std::vector<double> moment;    // 3 #groups
  std::vector<double> mean;      // 2 #groups
  std::vector<double> spread;    // 6 #groups
  std::vector<double> variance;  // 3 #groups
  std::size_t size() const { return mass.size(); }
};

// `cell` is scratch of (1/h + 1)² entries, all -1 on entry and on return.
PairGroups groupPair(const Tets& tets, Index j, Index k, double h, std::vector<int>& cell) {
  const int cells = int(std::lround(1.0 / h)) + 1;
  const double inverseH = 1.0 / h;
  PairGroups g;
  std::vector<double> sums;  // per group: Σ u b (2), Σ u b cᵀ (6), Σ u b bᵀ (3)
  std::vector<int> touched;
  const double* wj = tets.weights.col(j).data();
  const double* wk = tets.weights.col(k).data();
  for (Index t = 0; t < tets.volume.size(); ++t) {
    const double bj = wj[t], bk = wk[t], u = tets.volume[t] * bj * bk;
    if (!(u > 0.0)) continue;
    const int key = int(std::clamp(bj, 0.0, 1.0) * inverseH + 0.5) * cells + int(std::clamp(bk, 0.0, 1.0) * inverseH + 0.5);
    if (cell[std::size_t(key)] < 0) {
      cell[std::size_t(key)] = int(g.size());
      touched.push_back(key);
      g.mass.push_back(0.0);
      g.moment.resize(g.moment.size() + 3, 0.0);
      sums.resize(sums.size() + 11, 0.0);
    }
    const std::size_t c = std::size_t(cell[std::size_t(key)]);
    const Eigen::RowVector3d uc = u * tets.centroid.row(t);
    g.mass[c] += u;
    Eigen::Map<Eigen::RowVector3d>(&g.moment[3 * c]) += uc;
    double* s = &sums[11 * c];
    s[0] += u * bj;
    s[1] += u * bk;
    Eigen::Map<Eigen::RowVector3d>(s + 2) += bj * uc;
    Eigen::Map<Eigen::RowVector3d>(s + 5) += bk * uc;
    s[8] += u * bj * bj;
    s[9] += u * bj * bk;
    s[10] += u * bk * bk;
  }
  for (int key : touched) cell[std::size_t(key)] = -1;
  g.mean.resize(2 * g.size());
  g.spread.resize(6 * g.size());
  g.variance.resize(3 * g.size());
  // Central moments from raw ones: Σ u (b - b̄) xᵀ = Σ u b xᵀ - b̄ Σ u xᵀ. Within a cell b varies by h at
  // most, so the cancellation costs a few of the 16 digits (about 2 log10(1/h) for the variance).
  for (std::size_t c = 0; c < g.size(); ++c) {
    const double* s = &sums[11 * c];
    const Eigen::Map<const Eigen::RowVector3d> moment(&g.moment[3 * c]);
    const double mj = s[0] / g.mass[c], mk = s[1] / g.mass[c];
    g.mean[2 * c] = mj;
    g.mean[2 * c + 1] = mk;
    Eigen::Map<Eigen::RowVector3d>(&g.spread[6 * c]) = Eigen::Map<const Eigen::RowVector3d>(s + 2) - mj * moment;
    Eigen::Map<Eigen::RowVector3d>(&g.spread[6 * c + 3]) = Eigen::Map<const Eigen::RowVector3d>(s + 5) - mk * moment;
    g.variance[3 * c] = s[8] - mj * s[0];
    g.variance[3 * c + 1] = s[9] - mj * s[1];
    g.variance[3 * c + 2] = s[10] - mk * s[1];
  }
  return g;
}

// Groups of every bone pair some vertex uses, concatenated; groups of pair (j, k) are
// [offset[pairIndex(j, k)], offset[pairIndex(j, k) + 1]).
struct Groups {
  PairGroups all;
  std::vector<std::size_t> offset;
};

Groups groupTets(const Tets& tets, const Eigen::MatrixXd& W, double h) {
  const Index bones = W.cols();
  std::vector<char> used(std::size_t(bones * bones), 0);
  std::vector<Pair> pairs;
  for (Index i = 0; i < W.rows(); ++i) {
    activePairs(W.row(i), pairs);
    for (const Pair& p : pairs) used[std::size_t(pairIndex(p.j, p.k, bones))] = 1;
  }
  std::vector<PairGroups> perPair(used.size());
  const int cells = int(std::lround(1.0 / h)) + 1;
  tbb::parallel_for(tbb::blocked_range<Index>(0, bones * bones, 1), [&](const tbb::blocked_range<Index>& r) {
    std::vector<int> cell(std::size_t(cells) * std::size_t(cells), -1);
    for (Index p = r.begin(); p < r.end(); ++p)
      if (used[std::size_t(p)]) perPair[std::size_t(p)] = groupPair(tets, p / bones, p % bones, h, cell);
  });
  Groups g;
  g.offset.assign(used.size() + 1, 0);
  for (std::size_t p = 0; p < perPair.size(); ++p) g.offset[p + 1] = g.offset[p] + perPair[p].size();
  for (PairGroups& p : perPair) {
    g.all.mass.insert(g.all.mass.end(), p.mass.begin(), p.mass.end());
    g.all.moment.insert(g.all.moment.end(), p.moment.begin(), p.moment.end());
    g.all.mean.insert(g.all.mean.end(), p.mean.begin(), p.mean.end());
    g.all.spread.insert(g.all.spread.end(), p.spread.begin(), p.spread.end());
    g.all.variance.insert(g.all.variance.end(), p.variance.begin(), p.variance.end());
    p = PairGroups();
  }
  return g;
}

// Eq. 7 from its two sums; a vertex with no similar tet keeps its own position.
Eigen::RowVector3d centre(const Eigen::RowVector3d& numerator, double denominator, double noCentre,
                          const Eigen::RowVector3d& position) {
  return denominator > noCentre ? Eigen::RowVector3d(numerator / denominator) : position;
}

// Eq. 7 for vertex i against the groups.
Eigen::RowVector3d groupedCentre(const MatrixX3d& V, const Eigen::MatrixXd& W, const Groups& g, Index i,
                                 double inverseSigma2, double noCentre, std::vector<Pair>& pairs) {
  activePairs(W.row(i), pairs);
  double denominator = 0.0;
  Eigen::RowVector3d numerator = Eigen::RowVector3d::Zero();
  for (const Pair& p : pairs) {
    const std::size_t pair = std::size_t(pairIndex(p.j, p.k, W.cols()));
    double pairDenominator = 0.0;
    Eigen::RowVector3d pairNumerator = Eigen::RowVector3d::Zero();
    for (std::size_t c = g.offset[pair]; c < g.offset[pair + 1]; ++c) {
      const double d = p.wj * g.all.mean[2 * c + 1] - p.wk * g.all.mean[2 * c], x = d * d * inverseSigma2;
      if (x >= kMaxExponent) continue;
      const double e = std::exp(-x), e1 = -2.0 * d * inverseSigma2 * e, e2 = (2.0 * x - 1.0) * 2.0 * inverseSigma2 * e;
      const double* v = &g.all.variance[3 * c];
      const double mass = g.all.mass[c];
      // ∇d = (-w_pk, w_pj); ½ E'' ∇dᵀ variance ∇d as a fraction of the mass.
      const double curvature = 0.5 * e2 * (p.wk * p.wk * v[0] - 2.0 * p.wj * p.wk * v[1] + p.wj * p.wj * v[2]) / mass;
      const Eigen::Map<const Eigen::RowVector3d> moment(&g.all.moment[3 * c]), spreadJ(&g.all.spread[6 * c]),
          spreadK(&g.all.spread[6 * c + 3]);
      pairDenominator += (e + curvature) * mass;
      pairNumerator += (e + curvature) * moment + e1 * (p.wj * spreadK - p.wk * spreadJ);
    }
    denominator += p.wj * p.wk * pairDenominator;
    numerator += p.wj * p.wk * pairNumerator;
  }
  return centre(numerator, denominator, noCentre, V.row(i));
}

// Eq. 7 for vertex i, tet by tet; `weights` are the tets' weights by row (a tet's bones are read together).
Eigen::RowVector3d exactCentre(const MatrixX3d& V, const Eigen::MatrixXd& W, const Tets& tets,
                               const RowMajorMatrix& weights, Index i, double inverseSigma2, double noCentre,
                               std::vector<Pair>& pairs) {
  activePairs(W.row(i), pairs);
  if (pairs.empty()) return V.row(i);
  double denominator = 0.0;
  Eigen::RowVector3d numerator = Eigen::RowVector3d::Zero();
  for (Index t = 0; t < tets.volume.size(); ++t) {
    double s = 0.0;
    for (const Pair& p : pairs) {
      const double bj = weights(t, p.j), bk = weights(t, p.k), d = p.wj * bk - p.wk * bj;
      const double x = d * d * inverseSigma2;
      if (x < kMaxExponent) s += p.wj * p.wk * bj * bk * std::exp(-x);
    }
    denominator += s * tets.volume[t];
    numerator += s * tets.volume[t] * tets.centroid.row(t);
  }
  return centre(numerator, denominator, noCentre, V.row(i));
}

// Evaluates `one(i, pairs)` for the vertices `rows`, in parallel: #rows by 3.
template <class Centre>
MatrixX3d forRows(const Eigen::VectorXi& rows, Centre one) {
  MatrixX3d centres(rows.size(), 3);
  tbb::parallel_for(tbb::blocked_range<Index>(0, rows.size(), 16), [&](const tbb::blocked_range<Index>& r) {
    std::vector<Pair> pairs;
    for (Index row = r.begin(); row < r.end(); ++row) centres.row(row) = one(Index(rows[row]), pairs);
  });
  return centres;
}

}  // namespace

MatrixX3d computeRotationCenters(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W,
                                 const RotationCenterOptions& options) {
  checkInputs(V, T, W, options);
  const Tets tets = tetWeights(V, T, W);
  const Groups groups = groupTets(tets, W, options.clusterWidth);
  const double inverseSigma2 = 1.0 / (options.sigma * options.sigma), noCentre = kNoCentre * tets.volume.sum();
  return forRows(Eigen::VectorXi::LinSpaced(V.rows(), 0, int(V.rows()) - 1), [&](Index i, std::vector<Pair>& pairs) {
    return groupedCentre(V, W, groups, i, inverseSigma2, noCentre, pairs);
  });
}

MatrixX3d computeRotationCentersBruteForce(const MatrixX3d& V, const MatrixX4i& T, const Eigen::MatrixXd& W,
                                           const RotationCenterOptions& options, const Eigen::VectorXi& only) {
  checkInputs(V, T, W, options);
  if (only.size() > 0 && (only.minCoeff() < 0 || only.maxCoeff() >= V.rows()))
    throw UsageError("rotation centres: a vertex index to evaluate is out of range");
  const Tets tets = tetWeights(V, T, W);
  const RowMajorMatrix weights = tets.weights;
  const double inverseSigma2 = 1.0 / (options.sigma * options.sigma), noCentre = kNoCentre * tets.volume.sum();
  const Eigen::VectorXi all = Eigen::VectorXi::LinSpaced(V.rows(), 0, int(V.rows()) - 1);
  return forRows(only.size() > 0 ? only : all, [&](Index i, std::vector<Pair>& pairs) {
    return exactCentre(V, W, tets, weights, i, inverseSigma2, noCentre, pairs);
  });
}

}  // namespace vesalius::posing
