// Closest-point correspondences of the skin registration (skin_correspondences.h).
#include "skin_correspondences.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace vesalius::transfer::detail {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

MatrixX3d faceNormals(const MatrixX3d& V, const MatrixX3i& F) {
  MatrixX3d N(F.rows(), 3);
  tbb::parallel_for(Eigen::Index(0), F.rows(), [&](Eigen::Index f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    N.row(f) = (b - a).cross(c - a).stableNormalized().transpose();
  });
  return N;
}

MatrixX3d vertexNormals(const MatrixX3d& V, const MatrixX3i& F) {
  MatrixX3d N = MatrixX3d::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // twice the area times the normal
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < V.rows(); ++v) N.row(v) = N.row(v).stableNormalized();
  return N;
}

std::vector<std::vector<int>> skinNeighbours(Eigen::Index vertexCount, const MatrixX3i& F) {
  std::vector<std::vector<int>> adjacent(vertexCount);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      adjacent[F(f, k)].push_back(F(f, (k + 1) % 3));
      adjacent[F(f, (k + 1) % 3)].push_back(F(f, k));
    }
  for (auto& a : adjacent) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  return adjacent;
}

Target makeTarget(const MatrixX3d& Vt, const MatrixX3i& Ft) {
  return Target{Vt, TriangleTree(Vt, Ft), faceNormals(Vt, Ft), vertexNormals(Vt, Ft), {}, {}, 0};
}

Target makePartialTarget(const MatrixX3d& Vt, const MatrixX3i& Ft, const std::vector<int>& cut,
                         double reciprocalToleranceMm) {
  Target t = makeTarget(Vt, Ft);
  t.cutVertex.assign(std::size_t(Vt.rows()), 0);
  for (const int v : cut) t.cutVertex[std::size_t(v)] = 1;
  t.cutFace.assign(std::size_t(Ft.rows()), 0);
  for (Eigen::Index f = 0; f < Ft.rows(); ++f)
    t.cutFace[std::size_t(f)] = t.cutVertex[std::size_t(Ft(f, 0))] || t.cutVertex[std::size_t(Ft(f, 1))] ||
                                t.cutVertex[std::size_t(Ft(f, 2))];
  t.reciprocalToleranceMm = reciprocalToleranceMm;
  return t;
}

// forward: the closest points on the target of the rows of X.
std::vector<Pair> correspondences(const MatrixX3d& X, const MatrixX3i& Fs, const std::vector<ClosestPoint>& forward,
                                  const Target& target, const std::vector<SkinLandmark>& landmarks,
                                  const SkinRegistrationOptions& options) {
  const double minCos = std::cos(options.maxNormalAngleDeg * kPi / 180) - 1e-12;
  const MatrixX3d sourceNormals = vertexNormals(X, Fs);
  std::vector<Pair> pairs;
  // A partial target: how near the source surface comes to each forward pair's target point.
  std::vector<ClosestPoint> reciprocal;
  if (target.partial()) {
    MatrixX3d P(X.rows(), 3);
    for (Eigen::Index v = 0; v < X.rows(); ++v) P.row(v) = forward[v].point.transpose();
    reciprocal = TriangleTree(X, Fs).closest(P);
  }
  for (Eigen::Index v = 0; v < X.rows(); ++v) {
    if (sourceNormals.row(v).dot(target.faceNormals.row(forward[v].face)) < minCos) continue;
    if (target.partial()) {
      if (target.cutFace[std::size_t(forward[v].face)]) continue;
      if (std::sqrt(forward[v].squaredDistance) >
          std::sqrt(reciprocal[std::size_t(v)].squaredDistance) + target.reciprocalToleranceMm)
        continue;
    }
    pairs.push_back({{int(v), int(v), int(v)}, Eigen::Vector3d(1, 0, 0), forward[v].point, 1.0});
  }
  if (options.symmetric) {
    const TriangleTree sourceTree(X, Fs);
    const MatrixX3d sourceFaceNormals = faceNormals(X, Fs);
    const std::vector<ClosestPoint> backward = sourceTree.closest(target.V);
    const double weight = double(X.rows()) / double(target.V.rows());  // both directions weigh the same
    for (Eigen::Index t = 0; t < target.V.rows(); ++t) {
      if (target.partial() && target.cutVertex[std::size_t(t)]) continue;
      const ClosestPoint& c = backward[t];
      if (target.vertexNormals.row(t).dot(sourceFaceNormals.row(c.face)) >= minCos)
        pairs.push_back({{Fs(c.face, 0), Fs(c.face, 1), Fs(c.face, 2)}, c.barycentric, target.V.row(t), weight});
    }
  }
  for (const SkinLandmark& l : landmarks)
    pairs.push_back({{l.sourceVertex, l.sourceVertex, l.sourceVertex}, Eigen::Vector3d(1, 0, 0), l.target,
                     options.landmarkWeight});
  return pairs;
}

Eigen::Vector3d sourcePoint(const MatrixX3d& X, const Pair& p) {
  return p.barycentric[0] * X.row(p.vertices[0]).transpose() + p.barycentric[1] * X.row(p.vertices[1]).transpose() +
         p.barycentric[2] * X.row(p.vertices[2]).transpose();
}

SimilarityTransform compose(const SimilarityTransform& second, const SimilarityTransform& first) {
  SimilarityTransform t;
  t.scale = second.scale * first.scale;
  t.rotation = second.rotation * first.rotation;
  t.translation = second.apply(first.translation);
  return t;
}

}  // namespace vesalius::transfer::detail
