// Angle-weighted pseudonormal sign test (pseudonormal_sign.h).
#include "pseudonormal_sign.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>
#include <vector>

namespace vesalius::meshing::detail {

std::uint64_t PseudonormalSign::edgeKey(int a, int b) {
  return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
}

namespace {

// +1 if every piece of the surface (triangles connected through shared vertices) encloses a positive
// volume, -1 if every piece a negative one, 0 if they differ: a cavity or a piece turned inside out,
// where one orientation for all would put some voxels on the wrong side.
double outwardSign(const MatrixX3d& V, const MatrixX3i& F) {
  std::vector<int> parent(std::size_t(V.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[v] != v) {
      parent[v] = parent[parent[v]];  // path halving
      v = parent[v];
    }
    return v;
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 1; c < 3; ++c) parent[root(F(f, c))] = root(F(f, 0));
  std::unordered_map<int, double> volume;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    volume[root(F(f, 0))] += a.dot(b.cross(c)) / 6.0;  // as enclosedVolume, per piece
  }
  bool positive = false, negative = false;
  for (const auto& piece : volume) (piece.second < 0.0 ? negative : positive) = true;
  return positive && negative ? 0.0 : negative ? -1.0 : 1.0;
}

}  // namespace

PseudonormalSign::PseudonormalSign(const TriMesh& mesh) : F_(mesh.F) {
  const MatrixX3d& V = mesh.V;
  std::unordered_set<std::uint64_t> directed;
  for (Eigen::Index f = 0; f < F_.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (!directed.insert((std::uint64_t(std::uint32_t(F_(f, c))) << 32) | std::uint32_t(F_(f, (c + 1) % 3))).second)
        return;  // a directed edge twice: not a consistently oriented manifold
  for (std::uint64_t e : directed)
    if (!directed.count((e << 32) | (e >> 32))) return;  // an edge without its reverse: open
  const double outward = outwardSign(V, F_);
  if (outward == 0.0) return;
  faceNormals_.resize(F_.rows(), 3);
  vertexNormals_ = MatrixX3d::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F_.rows(); ++f) {
    Eigen::Vector3d n = (V.row(F_(f, 1)) - V.row(F_(f, 0))).cross(V.row(F_(f, 2)) - V.row(F_(f, 0)));
    if (n.norm() > 0.0) n = outward * n.normalized();
    faceNormals_.row(f) = n.transpose();
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d u = V.row(F_(f, (c + 1) % 3)) - V.row(F_(f, c)),
                            w = V.row(F_(f, (c + 2) % 3)) - V.row(F_(f, c));
      const double angle = std::atan2(u.cross(w).norm(), u.dot(w));
      vertexNormals_.row(F_(f, c)) += angle * n.transpose();
      // Each edge gets its two faces' normals (Eigen vectors start uninitialized: insert zero first).
      edgeNormals_.try_emplace(edgeKey(F_(f, c), F_(f, (c + 1) % 3)), Eigen::Vector3d::Zero()).first->second += n;
    }
  }
  usable_ = true;
}

bool PseudonormalSign::inside(const Eigen::Vector3d& p, const ClosestPoint& closest) const {
  const Eigen::Vector3d& b = closest.barycentric;
  const int zeros = (b.array() == 0.0).count();  // Ericson's closest point gives exact zeros off the face
  Eigen::Vector3d n = faceNormals_.row(closest.face).transpose();
  if (zeros == 2) {
    Eigen::Index corner = 0;
    b.maxCoeff(&corner);
    n = vertexNormals_.row(F_(closest.face, corner)).transpose();
  } else if (zeros == 1) {
    Eigen::Index opposite = 0;
    b.minCoeff(&opposite);
    n = edgeNormals_.at(edgeKey(F_(closest.face, (opposite + 1) % 3), F_(closest.face, (opposite + 2) % 3)));
  }
  return (p - closest.point).dot(n) < 0.0;
}

}  // namespace vesalius::meshing::detail
