#include "vesalius/transfer/skin_registration.h"

#include "skin_correspondences.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <Eigen/SVD>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

namespace vesalius::transfer {
namespace {

using detail::Pair;
using detail::Target;
using detail::correspondences;
using detail::sourcePoint;

void checkMesh(const MatrixX3d& V, const MatrixX3i& F, const std::string& name) {
  if (V.rows() == 0 || F.rows() == 0) throw BadInput("", "skin registration: the " + name + " is empty");
  TriMesh{V, F, {}, {}, {}, {}}.validate("skin registration " + name);
}

}  // namespace

void detail::checkOptions(const SkinRegistrationOptions& o) {
  const auto usage = [](const std::string& what) { throw UsageError("skin registration: " + what); };
  if (o.iterations < 1) usage("iterations must be at least 1");
  if (!(o.stiffnessStart >= 0 && o.stiffnessStart <= 1 && o.stiffnessEnd >= 0 && o.stiffnessEnd <= o.stiffnessStart))
    usage("stiffness must go down within [0, 1]");
  if (o.ringsEnd < 1 || o.ringsEnd > o.ringsStart) usage("cluster rings must go down and stay at least 1");
  if (!(o.beta >= 0 && o.beta <= 1)) usage("beta must lie in [0, 1]");
  if (!(o.maxNormalAngleDeg > 0 && o.maxNormalAngleDeg <= 180)) usage("the normal angle must lie in (0, 180]");
  if (o.alignIterations < 0) usage("alignment iterations must not be negative");
  if (!(o.landmarkWeight >= 0 && std::isfinite(o.landmarkWeight))) usage("the landmark weight must be >= 0");
}

namespace {

void checkLandmarks(const std::vector<SkinLandmark>& landmarks, Eigen::Index vertexCount) {
  for (std::size_t l = 0; l < landmarks.size(); ++l) {
    if (landmarks[l].sourceVertex < 0 || landmarks[l].sourceVertex >= vertexCount)
      throw BadInput("", "skin registration: landmark " + std::to_string(l) + " names no source vertex");
    if (!landmarks[l].target.allFinite())
      throw BadInput("", "skin registration: landmark " + std::to_string(l) + " is not finite");
  }
}

// Each vertex's neighbours by graph distance up to `rings`: members[v] lists them nearest ring first
// (v itself first), and levelEnd[v][r] is the count within r rings.
struct Rings {
  std::vector<std::vector<int>> members;
  std::vector<std::vector<int>> levelEnd;
};

Rings buildRings(Eigen::Index vertexCount, const MatrixX3i& F, int rings) {
  const std::vector<std::vector<int>> adjacent = detail::skinNeighbours(vertexCount, F);
  Rings result{std::vector<std::vector<int>>(vertexCount), std::vector<std::vector<int>>(vertexCount)};
  using Range = tbb::blocked_range<Eigen::Index>;
  tbb::parallel_for(Range(0, vertexCount, 256), [&](const Range& range) {
    std::vector<Eigen::Index> seenBy(vertexCount, -1);  // the vertex whose search last met each vertex
    for (Eigen::Index v = range.begin(); v != range.end(); ++v) {
      std::vector<int>& m = result.members[v];
      std::vector<int>& ends = result.levelEnd[v];
      m = {int(v)};
      ends = {1};
      seenBy[v] = v;
      for (int r = 1; r <= rings; ++r) {
        for (std::size_t i = r == 1 ? 0 : std::size_t(ends[r - 2]); i < std::size_t(ends[r - 1]); ++i)
          for (const int w : adjacent[m[i]])
            if (seenBy[w] != v) {
              seenBy[w] = v;
              m.push_back(w);
            }
        ends.push_back(int(m.size()));
      }
    }
  });
  return result;
}

Eigen::Vector3d areaCentroid(const MatrixX3d& V, const MatrixX3i& F) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double area = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const double A = (b - a).cross(c - a).norm();
    sum += A * (a + b + c) / 3;
    area += A;
  }
  if (!(area > 0)) throw BadInput("", "skin registration: a skin has no area");
  return sum / area;
}

// Step 1: landmarks or centroids, then similarity ICP on the pairs above.
SimilarityTransform similarityAlignment(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3i& Ft,
                                     const Target& target, const std::vector<SkinLandmark>& landmarks,
                                     const SkinRegistrationOptions& options) {
  SimilarityTransform total;
  if (landmarks.size() >= 3) {
    MatrixX3d from(landmarks.size(), 3), to(landmarks.size(), 3);
    for (std::size_t l = 0; l < landmarks.size(); ++l) {
      from.row(l) = Vs.row(landmarks[l].sourceVertex);
      to.row(l) = landmarks[l].target.transpose();
    }
    total = fitSimilarity(from, to, Eigen::VectorXd(), true);
  } else {
    total.translation = areaCentroid(target.V, Ft) - areaCentroid(Vs, Fs);
  }
  for (int it = 0; it < options.alignIterations; ++it) {
    const MatrixX3d X = total.apply(Vs);
    const std::vector<Pair> pairs = correspondences(X, Fs, target.tree.closest(X), target, landmarks, options);
    if (pairs.size() < 3) break;
    MatrixX3d from(pairs.size(), 3), to(pairs.size(), 3);
    Eigen::VectorXd w(pairs.size());
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      from.row(p) = sourcePoint(X, pairs[p]).transpose();
      to.row(p) = pairs[p].target.transpose();
      w[p] = pairs[p].weight;
    }
    total = detail::compose(fitSimilarity(from, to, w, true), total);
  }
  return total;
}

// Step 2: each vertex's wanted position y (#V by 3) and whether any pair reaches it.
MatrixX3d wantedPositions(const MatrixX3d& X, const std::vector<Pair>& pairs, std::vector<char>& reached) {
  MatrixX3d sum = MatrixX3d::Zero(X.rows(), 3);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(X.rows());
  for (const Pair& p : pairs) {
    const Eigen::RowVector3d shift = (p.target - sourcePoint(X, p)).transpose();
    for (int k = 0; k < 3; ++k) {
      const double w = p.weight * p.barycentric[k];
      sum.row(p.vertices[k]) += w * (X.row(p.vertices[k]) + shift);
      weight[p.vertices[k]] += w;
    }
  }
  reached.assign(X.rows(), 0);
  MatrixX3d Y = X;
  for (Eigen::Index v = 0; v < X.rows(); ++v)
    if (weight[v] > 0) {
      Y.row(v) = sum.row(v) / weight[v];
      reached[v] = 1;
    }
  return Y;
}

// Step 3: the shape-matching goals of the rest shape Q fitted to Y with clusters of `rings` rings.
MatrixX3d shapeMatchingGoals(const MatrixX3d& Q, const MatrixX3d& Y, const Rings& clusters, int rings,
                             double beta) {
  const Eigen::Index n = Q.rows();
  std::vector<Eigen::Matrix3d> T(n);
  MatrixX3d qMean(n, 3), yMean(n, 3);
  tbb::parallel_for(Eigen::Index(0), n, [&](Eigen::Index k) {
    const std::vector<int>& m = clusters.members[k];
    const int count = clusters.levelEnd[k][rings];
    Eigen::RowVector3d qc = Eigen::RowVector3d::Zero(), yc = Eigen::RowVector3d::Zero();
    for (int i = 0; i < count; ++i) {
      qc += Q.row(m[i]);
      yc += Y.row(m[i]);
    }
    qc /= count;
    yc /= count;
    Eigen::Matrix3d Apq = Eigen::Matrix3d::Zero(), Aqq = Eigen::Matrix3d::Zero();
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d q = (Q.row(m[i]) - qc).transpose(), p = (Y.row(m[i]) - yc).transpose();
      Apq += p * q.transpose();
      Aqq += q * q.transpose();
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(Apq, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d signs(1, 1, (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1);
    const Eigen::Matrix3d R = svd.matrixU() * signs.asDiagonal() * svd.matrixV().transpose();
    // Regularised toward R: a surface patch has (almost) no spread along its normal.
    const double eps = 1e-2 * Aqq.trace() + 1e-12;
    const Eigen::Matrix3d A = (Apq + eps * R) * (Aqq + eps * Eigen::Matrix3d::Identity()).inverse();
    T[k] = beta * A + (1 - beta) * R;
    qMean.row(k) = qc;
    yMean.row(k) = yc;
  });
  MatrixX3d G(n, 3);
  tbb::parallel_for(Eigen::Index(0), n, [&](Eigen::Index i) {
    // Ring membership is symmetric, so the clusters holding i are the centres within `rings` of i.
    const std::vector<int>& m = clusters.members[i];
    const int count = clusters.levelEnd[i][rings];
    Eigen::RowVector3d g = Eigen::RowVector3d::Zero();
    for (int j = 0; j < count; ++j) {
      const int k = m[j];
      g += (Q.row(i) - qMean.row(k)) * T[k].transpose() + yMean.row(k);
    }
    G.row(i) = g / count;
  });
  return G;
}

}  // namespace

SimilarityTransform alignSkin(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3d& Vt, const MatrixX3i& Ft,
                                   const SkinRegistrationOptions& options, const std::vector<SkinLandmark>& landmarks) {
  detail::checkOptions(options);
  checkMesh(Vs, Fs, "source skin");
  checkMesh(Vt, Ft, "target skin");
  checkLandmarks(landmarks, Vs.rows());
  return similarityAlignment(Vs, Fs, Ft, detail::makeTarget(Vt, Ft), landmarks, options);
}

SkinRegistration registerSkin(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3d& Vt, const MatrixX3i& Ft,
                              const SkinRegistrationOptions& options, const std::vector<SkinLandmark>& landmarks) {
  detail::checkOptions(options);
  checkMesh(Vs, Fs, "source skin");
  checkMesh(Vt, Ft, "target skin");
  checkLandmarks(landmarks, Vs.rows());
  const Target target = detail::makeTarget(Vt, Ft);

  SkinRegistration result;
  if (options.align) result.alignment = similarityAlignment(Vs, Fs, Ft, target, landmarks, options);
  std::vector<char> reached;
  result.V = detail::deformOntoTarget(result.alignment.apply(Vs), Fs, target, landmarks, options, result.meanDistance,
                                      reached);
  std::tie(result.finalMeanDistance, result.finalMaxDistance) = detail::distances(target.tree.closest(result.V));
  return result;
}

namespace detail {

std::pair<double, double> distances(const std::vector<ClosestPoint>& closest) {
  double sum = 0, largest = 0;
  for (const ClosestPoint& p : closest) {
    const double d = std::sqrt(p.squaredDistance);
    sum += d;
    largest = std::max(largest, d);
  }
  return {sum / double(closest.size()), largest};
}

MatrixX3d deformOntoTarget(const MatrixX3d& Q, const MatrixX3i& Fs, const Target& target,
                           const std::vector<SkinLandmark>& landmarks, const SkinRegistrationOptions& options,
                           std::vector<double>& meanDistance, std::vector<char>& reached) {
  const Rings clusters = buildRings(Q.rows(), Fs, options.ringsStart);
  MatrixX3d X = Q;
  for (int it = 0; it < options.iterations; ++it) {
    const double t = options.iterations == 1 ? 1.0 : double(it) / double(options.iterations - 1);
    const double s = options.stiffnessStart + t * (options.stiffnessEnd - options.stiffnessStart);
    const int rings = int(std::lround(options.ringsStart + t * (options.ringsEnd - options.ringsStart)));
    const std::vector<ClosestPoint> forward = target.tree.closest(X);
    meanDistance.push_back(distances(forward).first);
    const MatrixX3d Y = wantedPositions(X, correspondences(X, Fs, forward, target, landmarks, options), reached);
    const MatrixX3d G = shapeMatchingGoals(Q, Y, clusters, rings, options.beta);
    for (Eigen::Index v = 0; v < X.rows(); ++v)
      X.row(v) = reached[v] ? Eigen::RowVector3d(s * G.row(v) + (1 - s) * Y.row(v)) : Eigen::RowVector3d(G.row(v));
  }
  return X;
}

}  // namespace detail

}  // namespace vesalius::transfer
