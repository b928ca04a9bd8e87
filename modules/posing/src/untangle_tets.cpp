// Local untangling of a skinned tet mesh (untangle_tets.h): regions around the bad tets, each minimised by
// L-BFGS under the regularised barrier of Garanzha et al. 2021 with ε decreasing.
#include "vesalius/posing/untangle_tets.h"

#include "rest_rig.h"

#include "vesalius/core/error.h"
#include "vesalius/linalg/determinant.h"

#include <tbb/parallel_for.h>

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

namespace vesalius::posing {

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

// χ(D, ε) = (D + sqrt(ε² + D²)) / 2, written for D ≤ 0 without the cancellation (the paper's form).
double chi(double D, double epsilon) {
  const double root = std::sqrt(epsilon * epsilon + D * D);
  return D > 0 ? 0.5 * (D + root) : 0.5 * epsilon * epsilon / (root - D);
}

double chiDerivative(double D, double epsilon) { return 0.5 + 0.5 * D / std::sqrt(epsilon * epsilon + D * D); }

// The energy density of untangle_tets.h at the rest-to-posed map J, and dE/dJ if asked.
double density(const Eigen::Matrix3d& J, double epsilon, double theta, Eigen::Matrix3d* dJ) {
  const double D = J.determinant(), c = chi(D, epsilon), c23 = std::cbrt(c * c);
  const double f = J.squaredNorm() / c23, g = (D * D + 1) / c;
  if (dJ) {
    const double dc = chiDerivative(D, epsilon);
    const double byDet = (1 - theta) * (-2.0 / 3.0) * f * dc / c + theta * (2 * D - g * dc) / c;
    *dJ = (1 - theta) * (2 / c23) * J + byDet * determinantGradient(J);
  }
  return (1 - theta) * f + theta * g;
}

Eigen::Matrix3d edges(const Corners& p) {
  Eigen::Matrix3d E;
  for (int k = 0; k < 3; ++k) E.col(k) = (p.row(k + 1) - p.row(0)).transpose();
  return E;
}

// weight × density at posed corners p, with restInverse the inverse of the rest edges; adds the gradient with
// respect to the corners to `gradient` if given. Returns the energy; `det` gets D.
double weightedEnergy(const Corners& p, const Eigen::Matrix3d& restInverse, double weight, double epsilon,
                      double theta, Corners* gradient, double& det) {
  const Eigen::Matrix3d J = edges(p) * restInverse;
  det = J.determinant();
  Eigen::Matrix3d dJ;
  const double e = weight * density(J, epsilon, theta, gradient ? &dJ : nullptr);
  if (gradient) {
    const Eigen::Matrix3d dEdges = weight * dJ * restInverse.transpose();  // column k: corner k + 1
    gradient->row(0) -= dEdges.rowwise().sum().transpose();
    for (int k = 0; k < 3; ++k) gradient->row(k + 1) += dEdges.col(k).transpose();
  }
  return e;
}

// One region: its free vertices (sorted global indices) and the tets they touch, whose other corners stay.
class Region {
 public:
  Region(const MatrixX3d& restV, const MatrixX4i& T, const VertexTets& tetsOf, std::vector<int> free,
         const MatrixX3d& posedV)
      : free_(std::move(free)) {
    for (int v : free_) tets_.insert(tets_.end(), tetsOf.begin(v), tetsOf.end(v));
    std::sort(tets_.begin(), tets_.end());
    tets_.erase(std::unique(tets_.begin(), tets_.end()), tets_.end());
    double total = 0;
    for (int t : tets_) {
      Corners rest, posed;
      std::array<int, 4> local;
      for (int c = 0; c < 4; ++c) {
        rest.row(c) = restV.row(T(t, c));
        posed.row(c) = posedV.row(T(t, c));
        const auto it = std::lower_bound(free_.begin(), free_.end(), T(t, c));
        local[c] = it != free_.end() && *it == T(t, c) ? int(it - free_.begin()) : -1;
      }
      const Eigen::Matrix3d restEdges = edges(rest);
      restInverse_.push_back(restEdges.inverse());
      weight_.push_back(restEdges.determinant());
      total += weight_.back();
      corners_.push_back(posed);
      local_.push_back(local);
    }
    for (double& w : weight_) w /= total;  // energies of order 1 whatever the region's size
    size_ = std::cbrt(total / 6 / tets_.size());
  }

  Eigen::VectorXd positions(const MatrixX3d& posedV) const {
    Eigen::VectorXd x(3 * free_.size());
    for (std::size_t i = 0; i < free_.size(); ++i) x.segment<3>(3 * i) = posedV.row(free_[i]).transpose();
    return x;
  }
  void write(const Eigen::VectorXd& x, MatrixX3d& posedV) const {
    for (std::size_t i = 0; i < free_.size(); ++i) posedV.row(free_[i]) = x.segment<3>(3 * i).transpose();
  }
  double size() const { return size_; }  // a typical edge length

  // The region's energy at free positions x, its gradient into g (if not null) and the smallest D.
  double energy(const Eigen::VectorXd& x, double epsilon, double theta, Eigen::VectorXd* g, double& detMin) const {
    if (g) g->setZero(x.size());
    detMin = std::numeric_limits<double>::infinity();
    double E = 0;
    for (std::size_t t = 0; t < tets_.size(); ++t) {
      Corners p = corners_[t], grad = Corners::Zero();
      for (int c = 0; c < 4; ++c)
        if (local_[t][c] >= 0) p.row(c) = x.segment<3>(3 * local_[t][c]).transpose();
      double det;
      E += weightedEnergy(p, restInverse_[t], weight_[t], epsilon, theta, g ? &grad : nullptr, det);
      detMin = std::min(detMin, det);
      if (g)
        for (int c = 0; c < 4; ++c)
          if (local_[t][c] >= 0) g->segment<3>(3 * local_[t][c]) += grad.row(c).transpose();
    }
    return E;
  }

 private:
  std::vector<int> free_, tets_;
  std::vector<Eigen::Matrix3d> restInverse_;
  std::vector<double> weight_;
  std::vector<Corners> corners_;  // posed corners as skinned (the fixed ones stay so)
  std::vector<std::array<int, 4>> local_;  // per corner its index in free_, −1 if fixed
  double size_ = 1;
};

// L-BFGS (Nocedal and Wright 2006, Alg. 7.4: two-loop recursion, H0 = sᵀy / yᵀy) with a backtracking
// Armijo line search; the first step moves no vertex by more than a tenth of `size`. energy(x, g, detMin)
// returns the energy and writes its gradient and the smallest D. With `stopAtGoal`, stops early once every D
// reaches the goal (the vertices then stay nearer the skinned shape). Returns the final energy.
template <class Energy>
double minimizeLbfgs(const Energy& energy, Eigen::VectorXd& x, double size, const UntangleOptions& o, int iterations,
                     bool stopAtGoal) {
  Eigen::VectorXd g, gNext;
  double detMinNext;
  double E = energy(x, g, detMinNext);
  std::deque<std::pair<Eigen::VectorXd, Eigen::VectorXd>> pairs;  // (s, y), newest last
  for (int iteration = 0; iteration < iterations; ++iteration) {
    Eigen::VectorXd d = -g;
    std::vector<double> alpha(pairs.size());
    for (std::size_t k = pairs.size(); k-- > 0;) {
      alpha[k] = pairs[k].first.dot(d) / pairs[k].second.dot(pairs[k].first);
      d -= alpha[k] * pairs[k].second;
    }
    if (pairs.empty()) d *= 0.1 * size / std::max(g.lpNorm<Eigen::Infinity>(), 1e-300);
    else d *= pairs.back().first.dot(pairs.back().second) / pairs.back().second.squaredNorm();
    for (std::size_t k = 0; k < pairs.size(); ++k)
      d += pairs[k].first * (alpha[k] - pairs[k].second.dot(d) / pairs[k].second.dot(pairs[k].first));
    const double slope = g.dot(d);
    if (!(slope < 0)) return E;  // no descent left (gradient zero to rounding)
    double step = 1, ENext = 0;
    Eigen::VectorXd xNext;
    for (int halving = 0;; ++halving, step *= 0.5) {
      xNext = x + step * d;
      ENext = energy(xNext, gNext, detMinNext);
      if (ENext <= E + 1e-4 * step * slope) break;
      if (halving == 50) return E;
    }
    Eigen::VectorXd s = xNext - x, y = gNext - g;
    if (s.dot(y) > 1e-12 * s.norm() * y.norm()) pairs.emplace_back(std::move(s), std::move(y));
    if (int(pairs.size()) > o.history) pairs.pop_front();
    const double decrease = E - ENext;
    x = std::move(xNext);
    g = gNext;
    E = ENext;
    if (decrease <= 1e-12 * std::abs(E) || (stopAtGoal && detMinNext >= o.minVolumeRatio)) break;
  }
  return E;
}

// Minimises the region's energy from the skinned positions with ε decreasing (the paper's rule) until every
// tet reaches minVolumeRatio or the rounds run out, then relaxes it with the exact barrier; writes the free
// vertices back.
void untangleRegion(const Region& region, const UntangleOptions& o, MatrixX3d& posedV) {
  Eigen::VectorXd x = region.positions(posedV);
  double epsilon = 1, detMin;
  double EPrevious = region.energy(x, epsilon, o.theta, nullptr, detMin);
  for (int round = 0; round < o.maxRounds && detMin < o.minVolumeRatio; ++round) {
    const auto energy = [&](const Eigen::VectorXd& at, Eigen::VectorXd& g, double& atDetMin) {
      return region.energy(at, epsilon, o.theta, &g, atDetMin);
    };
    const double E = minimizeLbfgs(energy, x, region.size(), o, o.maxIterations, true);
    region.energy(x, epsilon, o.theta, nullptr, detMin);
    const double sigma = std::max(1 - E / EPrevious, 0.1);
    const double mu = (1 - sigma) * chi(detMin, epsilon);
    epsilon = detMin < mu ? 2 * std::sqrt(mu * (mu - detMin)) : 1e-10;
    EPrevious = region.energy(x, epsilon, o.theta, nullptr, detMin);
  }
  // The rounds stop at the goal while ε may still be large, and a large ε makes shrunken tets cheapest
  // (χ(D, ε) tends to ε/2, so both terms fall with D): the region is left smaller than at rest, a limb's
  // cross-section by several per cent. With every D positive, the exact barrier (ε → 0) keeps them so
  // along the line search, and its volume term, (D² + 1) / D, is least at the rest volume.
  if (detMin >= o.minVolumeRatio) {
    const auto exact = [&](const Eigen::VectorXd& at, Eigen::VectorXd& g, double& atDetMin) {
      return region.energy(at, 1e-10, o.theta, &g, atDetMin);
    };
    minimizeLbfgs(exact, x, region.size(), o, o.maxIterations, false);
  }
  region.write(x, posedV);
}

}  // namespace

TetUntangler::TetUntangler(const MatrixX3d& restV, const MatrixX4i& T, const Eigen::VectorXi& boneOfVertex,
                           const UntangleOptions& options)
    : restV_(restV), T_(T), fixed_(std::size_t(restV.rows())), options_(options) {
  const UntangleOptions& o = options;
  if (!(o.minVolumeRatio > 0 && o.minVolumeRatio < 1) || o.rings < 0 || o.maxRings < o.rings || !(o.theta >= 0) ||
      !(o.theta <= 1) || o.maxRounds < 1 || o.maxIterations < 1 || o.history < 1 || o.releaseRounds < 0)
    throw UsageError("untangle: options out of range (0 < minVolumeRatio < 1, 0 <= rings <= maxRings, 0 <= theta "
                     "<= 1, rounds, iterations and history >= 1, releaseRounds >= 0)");
  restVolume_ = checkedRestVolumes("untangle", restV, T, boneOfVertex);
  for (Eigen::Index v = 0; v < restV.rows(); ++v) fixed_[std::size_t(v)] = boneOfVertex[v] >= 0;
  tetsOf_ = vertexTets(T, restV.rows());
}

namespace {

std::vector<int> badTets(const MatrixX3d& V, const MatrixX4i& T, const Eigen::VectorXd& restVolume, double minRatio) {
  const Eigen::VectorXd volume = tetVolumes(V, T);
  std::vector<int> bad;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    if (!(volume[t] >= minRatio * restVolume[t])) bad.push_back(int(t));
  return bad;
}

int findRoot(std::vector<int>& parent, int v) {
  while (parent[std::size_t(v)] != v) v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
  return v;
}

}  // namespace

UntangleResult TetUntangler::operator()(MatrixX3d& posedV) const {
  if (posedV.rows() != restV_.rows())
    throw UsageError("untangle: " + std::to_string(posedV.rows()) + " posed vertices for " +
                     std::to_string(restV_.rows()) + " rest vertices");
  const auto start = std::chrono::steady_clock::now();
  UntangleResult result;
  std::vector<int> bad = badTets(posedV, T_, restVolume_, options_.minVolumeRatio);
  result.badBefore = long(bad.size());
  const MatrixX3d skinned = posedV;
  std::vector<bool> fixed = fixed_;  // less the bone vertices freed for folds between bones
  // A tet whose four corners are bone vertices (of two bones meeting) has nothing to move: left as it is.
  const auto movable = [&](std::vector<int> tets) {
    tets.erase(std::remove_if(tets.begin(), tets.end(),
                              [&](int t) {
                                for (int c = 0; c < 4; ++c)
                                  if (!fixed[std::size_t(T_(t, c))]) return false;
                                return true;
                              }),
               tets.end());
    return tets;
  };
  result.fixedBad = result.badBefore - long(movable(bad).size());
  for (int release = 0;; ++release) {
    for (int rings = options_.rings; !(bad = movable(bad)).empty() && rings <= options_.maxRings; ++rings) {
      std::vector<Region> regions;
      for (std::vector<int>& free : freeRegions(bad, rings, fixed))
        regions.emplace_back(restV_, T_, tetsOf_, std::move(free), posedV);
      tbb::parallel_for(std::size_t(0), regions.size(),
                        [&](std::size_t r) { untangleRegion(regions[r], options_, posedV); });
      result.regions += long(regions.size());
      bad = badTets(posedV, T_, restVolume_, options_.minVolumeRatio);
    }
    if (bad.empty() || release == options_.releaseRounds) break;
    for (int t : bad)
      for (int c = 0; c < 4; ++c)
        if (fixed[std::size_t(T_(t, c))]) {
          fixed[std::size_t(T_(t, c))] = false;
          ++result.releasedBoneVertices;
        }
  }
  result.badAfter = long(badTets(posedV, T_, restVolume_, options_.minVolumeRatio).size());
  const Eigen::VectorXd moves = (posedV - skinned).rowwise().norm();
  result.movedVertices = long((moves.array() > 0).count());
  result.maxMove = moves.size() > 0 ? moves.maxCoeff() : 0.0;
  for (Eigen::Index v = 0; v < moves.size(); ++v)
    if (fixed_[std::size_t(v)]) result.maxBoneMove = std::max(result.maxBoneMove, moves[v]);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

// The vertices of the bad tets grown by `rings` rings of tets, less the fixed ones, split into groups that
// share no tet: each is one region, solved on its own.
std::vector<std::vector<int>> TetUntangler::freeRegions(const std::vector<int>& bad, int rings,
                                                        const std::vector<bool>& fixed) const {
  std::vector<int> corners;
  for (int t : bad)
    for (int c = 0; c < 4; ++c) corners.push_back(T_(t, c));
  std::vector<int> all = vertexRings(T_, tetsOf_, corners, rings);
  std::vector<int> parent(fixed.size(), -1);
  for (int v : all)
    if (!fixed[std::size_t(v)]) parent[std::size_t(v)] = v;
  for (int v : all)
    for (const int* t = tetsOf_.begin(v); parent[std::size_t(v)] >= 0 && t != tetsOf_.end(v); ++t)
      for (int c = 0; c < 4; ++c) {
        const int w = T_(*t, c);
        if (parent[std::size_t(w)] >= 0) parent[std::size_t(findRoot(parent, w))] = findRoot(parent, v);
      }
  std::sort(all.begin(), all.end());
  std::vector<std::vector<int>> regions;
  std::vector<int> regionOfRoot(fixed.size(), -1);
  for (int v : all) {
    if (parent[std::size_t(v)] < 0) continue;
    int& r = regionOfRoot[std::size_t(findRoot(parent, v))];
    if (r < 0) {
      r = int(regions.size());
      regions.emplace_back();
    }
    regions[std::size_t(r)].push_back(v);
  }
  return regions;
}

double TetUntangler::tetEnergy(const Eigen::Matrix<double, 4, 3>& rest, const Eigen::Matrix<double, 4, 3>& posed,
                               double epsilon, double theta, Eigen::Matrix<double, 4, 3>* gradient) {
  const Eigen::Matrix3d restEdges = edges(rest);
  if (gradient) gradient->setZero();
  double det;
  return weightedEnergy(posed, restEdges.inverse(), restEdges.determinant() / 6, epsilon, theta, gradient, det);
}

}  // namespace vesalius::posing
