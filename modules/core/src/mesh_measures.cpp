#include "vesalius/core/mesh_measures.h"

#include <algorithm>
#include <numeric>
#include <utility>
#include <vector>

namespace vesalius {

EdgeCounts countEdges(const MatrixX3i& F) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(3 * F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  EdgeCounts counts;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    counts.boundary += j - i == 1;
    counts.nonManifold += j - i > 2;
    i = j;
  }
  return counts;
}

Eigen::VectorXi triangleComponentIds(Eigen::Index vertexCount, const MatrixX3i& F) {
  // Union-find with path halving.
  std::vector<int> parent(static_cast<std::size_t>(vertexCount));
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&parent](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 1; c < 3; ++c) parent[root(F(f, c))] = root(F(f, 0));
  std::vector<int> id(parent.size(), -1);
  int pieces = 0;
  Eigen::VectorXi piece(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    int& r = id[static_cast<std::size_t>(root(F(f, 0)))];
    if (r < 0) r = pieces++;
    piece[f] = r;
  }
  return piece;
}

int triangleComponents(Eigen::Index vertexCount, const MatrixX3i& F) {
  return F.rows() == 0 ? 0 : triangleComponentIds(vertexCount, F).maxCoeff() + 1;
}

Eigen::VectorXd triangleAreas(const MatrixX3d& V, const MatrixX3i& F) {
  Eigen::VectorXd area(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    area[f] = 0.5 * (V.row(F(f, 1)) - V.row(F(f, 0))).cross(V.row(F(f, 2)) - V.row(F(f, 0))).norm();
  return area;
}

double enclosedVolume(const MatrixX3d& V, const MatrixX3i& F) {
  double sixTimesVolume = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    sixTimesVolume += V.row(F(f, 0)).dot(V.row(F(f, 1)).cross(V.row(F(f, 2))));
  return sixTimesVolume / 6.0;
}

MatrixX3d vertexNormals(const MatrixX3d& V, const MatrixX3i& F) {
  MatrixX3d N = MatrixX3d::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a);  // twice the area times the unit normal
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index v = 0; v < N.rows(); ++v) {
    const double n = N.row(v).norm();
    if (n > 0) N.row(v) /= n;
  }
  return N;
}

Eigen::AlignedBox3d boundingBox(const MatrixX3d& V) {
  return V.rows() ? Eigen::AlignedBox3d(V.colwise().minCoeff().transpose(), V.colwise().maxCoeff().transpose())
                  : Eigen::AlignedBox3d();
}

}  // namespace vesalius
