// Bones bent inside their skin by a smooth, local displacement (bones_warped_into_skin.h).
#include "vesalius/transfer/bones_warped_into_skin.h"

#include "vesalius/core/error.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vesalius::transfer {

namespace {

// Wendland's C² kernel with support R.
double wendland(double r, double R) {
  const double q = r / R;
  return q >= 1.0 ? 0.0 : std::pow(1.0 - q, 4) * (4.0 * q + 1.0);
}

// Σ_i φ(|p − x_i|) c_i for every row p of P.
MatrixX3d kernelSum(const MatrixX3d& P, const MatrixX3d& X, const MatrixX3d& c, double R) {
  MatrixX3d u = MatrixX3d::Zero(P.rows(), 3);
  for (Eigen::Index p = 0; p < P.rows(); ++p)
    for (Eigen::Index i = 0; i < X.rows(); ++i) {
      const double w = wendland((P.row(p) - X.row(i)).norm(), R);
      if (w > 0) u.row(p) += w * c.row(i);
    }
  return u;
}

// The rows outside the skin that are not left alone (wanted finite).
std::vector<Eigen::Index> outsideRows(const SkinDistances& d, const Eigen::VectorXd& wanted) {
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < d.distance.size(); ++i)
    if (d.distance[i] > 0 && std::isfinite(wanted[i])) rows.push_back(i);
  return rows;
}

// One round's centres (the rows of X outside the skin) and coefficients (Φ + I) c = δ, at reach R.
void addRound(const MatrixX3d& X, const SkinDistances& d, const Eigen::VectorXd& wanted, double R, InsideSkinWarp& warp) {
  const std::vector<Eigen::Index> outside = outsideRows(d, wanted);
  const auto n = Eigen::Index(outside.size());
  MatrixX3d centres(n, 3), wishes(n, 3);
  for (Eigen::Index a = 0; a < n; ++a) {
    const Eigen::Index i = outside[std::size_t(a)];
    centres.row(a) = X.row(i);
    wishes.row(a) = -(d.distance[i] - wanted[i]) * d.outward.row(i);
  }
  Eigen::MatrixXd gram = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b) gram(a, b) += wendland((centres.row(a) - centres.row(b)).norm(), R);
  warp.radiiMm.push_back(R);
  warp.centres.push_back(centres);
  warp.coefficients.push_back(gram.ldlt().solve(Eigen::MatrixXd(wishes)));
}

}  // namespace

MatrixX3d InsideSkinWarp::apply(const MatrixX3d& P) const {
  MatrixX3d X = P;
  for (std::size_t r = 0; r < centres.size(); ++r) X += kernelSum(X, centres[r], coefficients[r], radiiMm[r]);
  return X;
}

namespace {

// What is left outside: the rows (outsideRows) and the sum of how far each is from its wanted depth.
// Fewer rows are better, and as many rows less far: the last vertex wedged between two sides, moved a
// little further each round, is progress too.
struct Left {
  long rows = 0;
  double excessMm = 0;
  bool operator<(const Left& o) const { return rows < o.rows || (rows == o.rows && excessMm < o.excessMm); }
};

Left leftOutside(const SkinDistances& d, const Eigen::VectorXd& wanted) {
  Left left;
  for (const Eigen::Index i : outsideRows(d, wanted)) ++left.rows, left.excessMm += d.distance[i] - wanted[i];
  return left;
}

// Up to `rounds` rounds at reach R from X (the warp so far, `left` outside of it), the rounds up to the
// one that left the least outside kept: where a vertex sits between two sides of the skin (between toes),
// pushing it out of one side can push it or its neighbours out of the other, and later rounds undo
// earlier gains. X and `left` become the kept rounds' result.
void addStage(MatrixX3d& X, Left& left, const SkinDistanceFunction& skin, const Eigen::VectorXd& wanted, double R,
              int rounds, InsideSkinWarp& warp) {
  MatrixX3d Y = X;
  SkinDistances d = skin(Y);
  std::size_t kept = warp.centres.size();
  for (int round = 0; round < rounds && left.rows > 0; ++round) {
    addRound(Y, d, wanted, R, warp);
    Y += kernelSum(Y, warp.centres.back(), warp.coefficients.back(), R);
    d = skin(Y);
    const Left now = leftOutside(d, wanted);
    if (now < left) left = now, kept = warp.centres.size(), X = Y;
  }
  warp.radiiMm.resize(kept);
  warp.centres.resize(kept);
  warp.coefficients.resize(kept);
}

}  // namespace

InsideSkinWarp warpIntoSkin(const MatrixX3d& V, const SkinDistanceFunction& skin, const Eigen::VectorXd& wantedDepth,
                            const InsideSkinWarpOptions& options) {
  if (V.rows() == 0) throw UsageError("warpIntoSkin: no vertices");
  const auto allowed = [](double w) { return w <= 0 || w == std::numeric_limits<double>::infinity(); };
  if (wantedDepth.size() != V.rows() || !std::all_of(wantedDepth.begin(), wantedDepth.end(), allowed))
    throw UsageError("warpIntoSkin: a wanted depth per vertex, at most 0 or +infinity, is needed");
  const auto positive = [](double R) { return R > 0; };
  if (!(options.marginMm >= 0 && options.rounds >= 0 && options.passes >= 1 &&
        std::all_of(options.radiiMm.begin(), options.radiiMm.end(), positive)))
    throw UsageError("warpIntoSkin: options out of range");
  InsideSkinWarp warp;
  MatrixX3d X = V;
  Left left = leftOutside(skin(X), wantedDepth);
  warp.outsideBefore = left.rows;
  for (int pass = 0; pass < options.passes && left.rows > 0; ++pass)
    for (const double R : options.radiiMm) addStage(X, left, skin, wantedDepth, R, options.rounds, warp);
  warp.outsideAfter = left.rows;
  warp.largestMoveMm = (X - V).rowwise().norm().maxCoeff();
  return warp;
}

InsideSkinWarp warpIntoSkin(const MatrixX3d& V, const SkinDistanceFunction& skin, const InsideSkinWarpOptions& options) {
  return warpIntoSkin(V, skin, Eigen::VectorXd::Constant(V.rows(), -options.marginMm), options);
}

}  // namespace vesalius::transfer
