// Edge and volume measures of triangle surfaces (surface_checks.h).
#include "vesalius/meshing/surface_checks.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>
#include <vector>

namespace vesalius::meshing {
namespace {

std::uint64_t edgeKey(int a, int b) {
  return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
}

// Number of faces using each undirected edge.
std::unordered_map<std::uint64_t, int> edgeUse(const TriMesh& mesh) {
  std::unordered_map<std::uint64_t, int> use;
  use.reserve(std::size_t(mesh.F.rows()) * 3 / 2 + 1);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++use[edgeKey(mesh.F(f, c), mesh.F(f, (c + 1) % 3))];
  return use;
}

int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

std::int64_t boundaryEdgeCount(const TriMesh& mesh) {
  const auto use = edgeUse(mesh);
  return std::count_if(use.begin(), use.end(), [](const auto& e) { return e.second == 1; });
}

std::int64_t nonManifoldEdgeCount(const TriMesh& mesh) {
  const auto use = edgeUse(mesh);
  return std::count_if(use.begin(), use.end(), [](const auto& e) { return e.second > 2; });
}

int faceComponentCount(const TriMesh& mesh) {
  const int faces = int(mesh.F.rows());
  std::vector<int> parent(faces);
  std::iota(parent.begin(), parent.end(), 0);
  std::unordered_map<std::uint64_t, int> firstFace;
  for (int f = 0; f < faces; ++f)
    for (int c = 0; c < 3; ++c) {
      const auto [it, inserted] = firstFace.emplace(edgeKey(mesh.F(f, c), mesh.F(f, (c + 1) % 3)), f);
      if (!inserted) parent[findRoot(parent, f)] = findRoot(parent, it->second);
    }
  int count = 0;
  for (int f = 0; f < faces; ++f) count += findRoot(parent, f) == f;
  return count;
}

double enclosedVolume(const TriMesh& mesh) {
  double sixTimes = 0.0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0));
    const Eigen::Vector3d b = mesh.V.row(mesh.F(f, 1));
    const Eigen::Vector3d c = mesh.V.row(mesh.F(f, 2));
    sixTimes += a.dot(b.cross(c));
  }
  return sixTimes / 6.0;
}

}  // namespace vesalius::meshing
