#include "vesalius/core/cap_holes.h"

#include <map>
#include <set>
#include <utility>
#include <vector>

namespace vesalius {

TriMesh capHoles(const TriMesh& mesh) {
  // Half-edges (a, b) of the faces; one whose reverse no face has borders a hole.
  std::set<std::pair<int, int>> halfEdges;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) halfEdges.emplace(mesh.F(f, k), mesh.F(f, (k + 1) % 3));
  std::multimap<int, std::pair<int, int>> boundary;  // a → (b, face)
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      if (!halfEdges.count({b, a})) boundary.emplace(a, std::make_pair(b, int(f)));
    }
  if (boundary.empty()) return mesh;

  // Loops: from a boundary half-edge, on along the half-edges that start where it ends, until the start.
  struct Edge {
    int a, b, face;
  };
  std::vector<std::vector<Edge>> loops;
  while (!boundary.empty()) {
    auto it = boundary.begin();
    const int start = it->first;
    std::vector<Edge> loop;
    while (it != boundary.end()) {
      const Edge e{it->first, it->second.first, it->second.second};
      boundary.erase(it);
      loop.push_back(e);
      if (e.b == start) break;
      it = boundary.find(e.b);
    }
    loops.push_back(std::move(loop));
  }

  std::size_t capFaces = 0;
  for (const auto& loop : loops) capFaces += loop.size();
  const Eigen::Index nV = mesh.V.rows(), nF = mesh.F.rows();
  TriMesh out = mesh;
  out.V.conservativeResize(nV + Eigen::Index(loops.size()), 3);
  out.F.conservativeResize(nF + Eigen::Index(capFaces), 3);
  Eigen::VectorXi vertexRows(out.V.rows()), faceRows(out.F.rows());
  for (Eigen::Index v = 0; v < nV; ++v) vertexRows[v] = int(v);
  for (Eigen::Index f = 0; f < nF; ++f) faceRows[f] = int(f);
  Eigen::Index f = nF;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const Eigen::Index centre = nV + Eigen::Index(l);
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (const Edge& e : loops[l]) sum += mesh.V.row(e.a);
    out.V.row(centre) = sum / double(loops[l].size());
    vertexRows[centre] = loops[l].front().a;
    for (const Edge& e : loops[l]) {
      out.F.row(f) << e.b, e.a, int(centre);
      faceRows[f++] = e.face;
    }
  }
  out.vertexAttributes = mesh.vertexAttributes.selectRows(vertexRows);
  out.faceAttributes = mesh.faceAttributes.selectRows(faceRows);
  if (mesh.FUV.rows() == nF && nF > 0) out.FUV = mesh.FUV(faceRows, Eigen::all);
  return out;
}

}  // namespace vesalius
