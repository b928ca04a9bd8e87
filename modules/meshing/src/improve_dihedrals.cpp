// Local smoothing of bad tets (see improve_dihedrals.h).
#include "improve_dihedrals.h"

#include "vesalius/core/tet_adjacency.h"
#include "vesalius/core/tet_quality.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace vesalius::meshing {
namespace {

// Faces on the outer boundary or between tets of different labels: their vertices stay where they are.
MatrixX3i fixedFaces(const TetMesh& mesh) {
  const auto labels = mesh.tetAttributes.integer.find(kLabel);
  if (labels == mesh.tetAttributes.integer.end()) return tetBoundary(mesh.T);
  std::vector<int> values(labels->second.data(), labels->second.data() + labels->second.size());
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  std::vector<Eigen::Vector3i> faces;
  for (int value : values) {
    std::vector<int> rows;
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
      if (labels->second(t) == value) rows.push_back(int(t));
    const MatrixX3i boundary = tetBoundary(mesh.T(rows, Eigen::all));
    for (Eigen::Index f = 0; f < boundary.rows(); ++f) faces.push_back(boundary.row(f).transpose());
  }
  MatrixX3i F(Eigen::Index(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) F.row(Eigen::Index(f)) = faces[f].transpose();
  return F;
}

using Edge = std::pair<int, int>;  // smaller vertex first
Edge edge(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

// The tets whose four vertices are all fixed cannot be smoothed: a sliver spanning a thin plate of bone
// from one side to the other, or lying flat on the surface. Splitting its longest edge that lies on no
// fixed face at the midpoint, and the tets around that edge with it, gives a free vertex smoothing can
// move. The surfaces are unchanged. Edges are chosen so that no tet is split twice.
// Returns whether any tet was split.
bool splitPinnedTets(TetMesh& mesh, std::vector<bool>& fixed, const std::set<Edge>& fixedEdges, double target) {
  const Eigen::VectorXd minDihedral = tetQuality(mesh.V, mesh.T).minDihedral;
  std::map<Edge, std::vector<int>> around;  // chosen edge -> tets holding it
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    const Eigen::Vector4i tet = mesh.T.row(t).transpose();
    if (minDihedral(t) >= target || !std::all_of(tet.data(), tet.data() + 4, [&](int v) { return fixed[v]; }))
      continue;
    std::optional<Edge> longest;
    double length = 0.0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (const Edge e = edge(tet(i), tet(j)); !fixedEdges.count(e))
          if (const double l = (mesh.V.row(e.first) - mesh.V.row(e.second)).norm(); l > length)
            longest = e, length = l;
    if (longest) around.emplace(*longest, std::vector<int>{});
  }
  if (around.empty()) return false;
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (const auto it = around.find(edge(mesh.T(t, i), mesh.T(t, j))); it != around.end())
          it->second.push_back(int(t));
  std::vector<bool> taken(std::size_t(mesh.T.rows()), false);
  std::vector<Eigen::Vector4i> added;
  std::vector<int> source;  // the tet each added one was split from
  for (const auto& [e, tets] : around) {
    if (std::any_of(tets.begin(), tets.end(), [&](int t) { return taken[std::size_t(t)]; })) continue;
    const int m = int(mesh.V.rows());
    mesh.V.conservativeResize(m + 1, 3);
    mesh.V.row(m) = 0.5 * (mesh.V.row(e.first) + mesh.V.row(e.second));
    fixed.push_back(false);
    for (int t : tets) {
      taken[std::size_t(t)] = true;
      Eigen::Vector4i half = mesh.T.row(t).transpose();  // one end replaced by the midpoint: same orientation
      for (int k = 0; k < 4; ++k) {
        if (half(k) == e.second) half(k) = m;
        if (mesh.T(t, k) == e.first) mesh.T(t, k) = m;
      }
      added.push_back(half);
      source.push_back(t);
    }
  }
  const Eigen::Index old = mesh.T.rows();
  mesh.T.conservativeResize(old + Eigen::Index(added.size()), 4);
  for (std::size_t n = 0; n < added.size(); ++n) mesh.T.row(old + Eigen::Index(n)) = added[n].transpose();
  Eigen::VectorXi rows(mesh.T.rows());
  rows.head(old) = Eigen::VectorXi::LinSpaced(old, 0, int(old) - 1);
  rows.tail(Eigen::Index(source.size())) = Eigen::Map<const Eigen::VectorXi>(source.data(), Eigen::Index(source.size()));
  mesh.tetAttributes = mesh.tetAttributes.selectRows(rows);
  return true;
}

class Star {
 public:
  Star(TetMesh& mesh, const std::vector<int>& tets, int vertex, double maxVolume)
      : mesh_(mesh), vertex_(vertex), maxVolume_(maxVolume), T_(mesh.T(tets, Eigen::all)) {}

  // Worst dihedral angle of the star with the vertex at p; -infinity if a tet would not be positive or
  // would exceed the volume bound.
  double score(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d saved = mesh_.V.row(vertex_);
    mesh_.V.row(vertex_) = p;
    const TetQuality q = tetQuality(mesh_.V, T_);
    mesh_.V.row(vertex_) = saved;
    const bool valid = (q.volume.array() > 0).all() && (maxVolume_ <= 0 || (q.volume.array() <= maxVolume_).all());
    return valid ? q.minDihedral.minCoeff() : -std::numeric_limits<double>::infinity();
  }

  // Pattern search: axis steps from a quarter of the mean edge length down to 1/32 of it, after trying
  // the star's centroid.
  void optimize() {
    Eigen::Vector3d best = mesh_.V.row(vertex_), centre = Eigen::Vector3d::Zero();
    double step = 0;
    for (Eigen::Index t = 0; t < T_.rows(); ++t)
      for (int k = 0; k < 4; ++k) {
        centre += mesh_.V.row(T_(t, k)).transpose() / double(4 * T_.rows());
        step += (mesh_.V.row(T_(t, k)) - mesh_.V.row(vertex_)).norm() / double(3 * T_.rows());
      }
    double bestScore = score(best);
    if (const double s = score(centre); s > bestScore) best = centre, bestScore = s;
    step *= 0.25;
    for (int level = 0; level < 4; ++level, step *= 0.5) {
      bool moved = true;
      for (int round = 0; moved && round < 4; ++round) {
        moved = false;
        for (int axis = 0; axis < 6; ++axis) {
          Eigen::Vector3d p = best;
          p(axis / 2) += axis % 2 ? step : -step;
          if (const double s = score(p); s > bestScore + 1e-9) best = p, bestScore = s, moved = true;
        }
      }
    }
    mesh_.V.row(vertex_) = best;
  }

 private:
  TetMesh& mesh_;
  int vertex_;
  double maxVolume_;
  MatrixX4i T_;
};

}  // namespace

void improveDihedrals(TetMesh& mesh, double targetDegrees, double maxVolume, int passes) {
  const MatrixX3i faces = fixedFaces(mesh);
  std::vector<bool> fixed(std::size_t(mesh.V.rows()), false);
  std::set<Edge> fixedEdges;
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      fixed[std::size_t(faces(f, k))] = true;
      fixedEdges.insert(edge(faces(f, k), faces(f, (k + 1) % 3)));
    }
  VertexTets tetsOf = vertexTets(mesh.T, mesh.V.rows());
  for (int pass = 0; pass < passes; ++pass) {
    if (splitPinnedTets(mesh, fixed, fixedEdges, targetDegrees)) tetsOf = vertexTets(mesh.T, mesh.V.rows());
    const Eigen::VectorXd minDihedral = tetQuality(mesh.V, mesh.T).minDihedral;
    bool any = false;
    for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
      if (minDihedral(t) >= targetDegrees) continue;
      any = true;
      for (int k = 0; k < 4; ++k) {
        const int v = mesh.T(t, k);
        if (!fixed[std::size_t(v)]) Star(mesh, tetsOf.of(v), v, maxVolume).optimize();
      }
    }
    if (!any) return;
  }
}

}  // namespace vesalius::meshing
