#include "vesalius/meshing/midpoint_subdivision.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace vesalius::meshing {

TriMesh subdivideMidpoints(const TriMesh& mesh, int levels) {
  MatrixX3d V = mesh.V;
  MatrixX3i F = mesh.F;
  for (int level = 0; level < levels; ++level) {
    std::unordered_map<std::uint64_t, int> midpoint;
    midpoint.reserve(std::size_t(F.rows()) * 2);
    std::vector<Eigen::Vector3d> added;
    const auto mid = [&](int a, int b) {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint32_t(std::max(a, b));
      const auto [it, fresh] = midpoint.emplace(key, int(V.rows() + Eigen::Index(added.size())));
      if (fresh) added.push_back(0.5 * (V.row(a) + V.row(b)).transpose());
      return it->second;
    };
    MatrixX3i next(4 * F.rows(), 3);
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.row(4 * f) << a, ab, ca;
      next.row(4 * f + 1) << ab, b, bc;
      next.row(4 * f + 2) << ca, bc, c;
      next.row(4 * f + 3) << ab, bc, ca;
    }
    const Eigen::Index old = V.rows();
    V.conservativeResize(old + Eigen::Index(added.size()), 3);
    for (std::size_t i = 0; i < added.size(); ++i) V.row(old + Eigen::Index(i)) = added[i].transpose();
    F = std::move(next);
  }
  TriMesh out;
  out.V = std::move(V);
  out.F = std::move(F);
  return out;
}

int midpointLevelsFor(const TriMesh& mesh, double maxEdge) {
  if (mesh.F.rows() == 0 || !(maxEdge > 0)) return 0;
  double sum = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) sum += (mesh.V.row(mesh.F(f, k)) - mesh.V.row(mesh.F(f, (k + 1) % 3))).norm();
  const double mean = sum / double(3 * mesh.F.rows());
  return mean <= maxEdge ? 0 : int(std::ceil(std::log2(mean / maxEdge)));
}

}  // namespace vesalius::meshing
