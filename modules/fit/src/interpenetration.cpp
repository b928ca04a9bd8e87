// Interpenetration removal between fitted organs (interpenetration.h, Wang et al. 2021, §4.1.4).
#include "vesalius/fit/interpenetration.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_adjacency.h"
#include "vesalius/core/tet_locator.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fem/static_equilibrium.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace vesalius::fit {

namespace {

std::vector<int> boundaryVertices(const MatrixX4i& T) {
  const MatrixX3i F = tetBoundary(T);
  std::vector<int> v(F.data(), F.data() + F.size());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// The rows of `boundary` whose vertex lies in (or on) a tet of the other mesh.
std::vector<int> verticesInside(const MatrixX3d& V, const std::vector<int>& boundary, const TetLocator& other) {
  std::vector<char> inside(boundary.size(), 0);
  tbb::parallel_for(std::size_t(0), boundary.size(), [&](std::size_t i) {
    inside[i] = other.locate(V.row(boundary[i]).transpose()).has_value();
  });
  std::vector<int> found;
  for (std::size_t i = 0; i < boundary.size(); ++i)
    if (inside[i]) found.push_back(boundary[i]);
  return found;
}

// Marks the tets holding a vertex within `rings` rings of the seeds.
void growRegion(const MatrixX4i& T, const VertexTets& tetsOf, const std::vector<int>& seeds, int rings,
                std::vector<char>& region) {
  for (int v : vertexRings(T, tetsOf, seeds, rings))
    for (const int* t = tetsOf.begin(v); t != tetsOf.end(v); ++t) region[std::size_t(*t)] = 1;
}

// Where each penetrating vertex is pulled: `share` of the way to the other mesh's nearest surface point,
// plus the clearance in that direction.
MatrixX3d contactTargets(const MatrixX3d& V, const std::vector<int>& penetrating, const TriangleTree& otherSurface,
                         double share, double clearance) {
  MatrixX3d targets(Eigen::Index(penetrating.size()), 3);
  for (std::size_t i = 0; i < penetrating.size(); ++i) {
    const Eigen::Vector3d p = V.row(penetrating[i]).transpose();
    const Eigen::Vector3d toSurface = otherSurface.closest(p).point - p;
    const double depth = toSurface.norm();
    const Eigen::Vector3d out = depth > 0 ? Eigen::Vector3d(toSurface / depth) : Eigen::Vector3d::Zero();
    targets.row(Eigen::Index(i)) = (p + share * toSurface + clearance * out).transpose();
  }
  return targets;
}

// The contact region of one mesh as a body of its own: its tets, their vertices, and which of those the
// rest of the mesh also uses (the border, held in place).
struct Region {
  MatrixX3d V;
  MatrixX4i T;
  std::vector<int> meshVertex;   // region vertex -> mesh vertex
  std::vector<int> regionVertex;  // mesh vertex -> region vertex, -1 outside
  std::vector<char> border;       // per region vertex
};

Region extractRegion(const MatrixX3d& V, const MatrixX4i& T, const std::vector<char>& inRegion) {
  Region r;
  r.regionVertex.assign(std::size_t(V.rows()), -1);
  std::vector<char> usedOutside(std::size_t(V.rows()), 0);
  std::vector<int> tets;
  for (int t = 0; t < T.rows(); ++t) {
    if (!inRegion[std::size_t(t)]) {
      for (int c = 0; c < 4; ++c) usedOutside[std::size_t(T(t, c))] = 1;
      continue;
    }
    tets.push_back(t);
    for (int c = 0; c < 4; ++c)
      if (r.regionVertex[std::size_t(T(t, c))] < 0) {
        r.regionVertex[std::size_t(T(t, c))] = int(r.meshVertex.size());
        r.meshVertex.push_back(T(t, c));
      }
  }
  r.V.resize(Eigen::Index(r.meshVertex.size()), 3);
  for (std::size_t i = 0; i < r.meshVertex.size(); ++i) {
    r.V.row(Eigen::Index(i)) = V.row(r.meshVertex[i]);
    r.border.push_back(usedOutside[std::size_t(r.meshVertex[i])]);
  }
  r.T.resize(Eigen::Index(tets.size()), 4);
  for (std::size_t k = 0; k < tets.size(); ++k)
    for (int c = 0; c < 4; ++c) r.T(Eigen::Index(k), c) = r.regionVertex[std::size_t(T(tets[k], c))];
  return r;
}

// Zero-rest-length springs on region vertices: each vertex as the material point at one of its tets' corners.
class VertexSprings {
 public:
  explicit VertexSprings(const MatrixX4i& T) : cornerOf_(std::size_t(T.maxCoeff() + 1), {-1, 0}) {
    for (int t = 0; t < T.rows(); ++t)
      for (int c = 0; c < 4; ++c)
        if (cornerOf_[std::size_t(T(t, c))].first < 0) cornerOf_[std::size_t(T(t, c))] = {t, c};
  }
  void add(int vertex, const Eigen::Vector3d& target, double stiffness) {
    const auto [tet, corner] = cornerOf_[std::size_t(vertex)];
    springs_.points.push_back({tet, Eigen::Vector4d::Unit(corner)});
    targets_.push_back(target);
    stiffness_.push_back(stiffness);
  }
  PointSprings springs() const {
    PointSprings s = springs_;
    s.targets.resize(Eigen::Index(targets_.size()), 3);
    for (std::size_t i = 0; i < targets_.size(); ++i) s.targets.row(Eigen::Index(i)) = targets_[i].transpose();
    s.stiffness = Eigen::Map<const Eigen::VectorXd>(stiffness_.data(), Eigen::Index(stiffness_.size()));
    return s;
  }

 private:
  std::vector<std::pair<int, int>> cornerOf_;
  PointSprings springs_;
  std::vector<Eigen::Vector3d> targets_;
  std::vector<double> stiffness_;
};

// The region's FEM solve (see the header); returns the mesh's positions with the region's free vertices moved.
MatrixX3d pushApart(const MatrixX3d& V, const MatrixX4i& T, const std::vector<char>& inRegion,
                    const std::vector<int>& penetrating, const MatrixX3d& targets, const InterpenetrationOptions& o) {
  const Region r = extractRegion(V, T, inRegion);
  const PlasticFem fem(r.V, r.T, StableNeoHookean::fromYoungPoisson(1.0, o.poissonRatio));
  const double unit = fem.material().mu * std::cbrt(fem.restVolumes().mean());
  VertexSprings springs(r.T);
  // Weak springs on every other vertex keep a region without border (a small mesh wholly in contact)
  // from drifting or turning freely, which leaves the Newton matrix singular.
  for (std::size_t i = 0; i < r.meshVertex.size(); ++i)
    springs.add(int(i), r.V.row(Eigen::Index(i)).transpose(), (r.border[i] ? o.holdStiffness : o.anchorStiffness) * unit);
  for (std::size_t k = 0; k < penetrating.size(); ++k)
    springs.add(r.regionVertex[std::size_t(penetrating[k])], targets.row(Eigen::Index(k)).transpose(),
                o.contactStiffness * unit);
  const Eigen::VectorXd s = identityPlasticStrain().replicate(r.T.rows(), 1);
  const EquilibriumResult solved =
      solveStaticEquilibrium(fem, s, springs.springs(), PlasticFem::flatten(r.V), EquilibriumOptions{200, 1e-6});
  if (!solved.converged)
    throw NumericalFailure("interpenetration removal: the contact solve did not converge (residual " +
                           std::to_string(solved.residual) + " after " + std::to_string(solved.iterations) + " Newton steps)");
  if (!(fem.elasticJacobians(solved.x, s).minCoeff() > 0))
    throw NumericalFailure("interpenetration removal: pushing the meshes apart would invert a tet");
  MatrixX3d moved = V;
  const MatrixX3d x = PlasticFem::unflatten(solved.x);
  for (std::size_t i = 0; i < r.meshVertex.size(); ++i)
    if (!r.border[i]) moved.row(r.meshVertex[i]) = x.row(Eigen::Index(i));
  return moved;
}

// One mesh of the pair, as the rounds see it.
struct Side {
  const MatrixX4i& T;
  MatrixX3d V;
  MatrixX3i F;
  std::vector<int> boundary;
  VertexTets tetsOfVertex;
  std::vector<char> region;

  explicit Side(const TetMesh& mesh)
      : T(mesh.T), V(mesh.V), F(tetBoundary(mesh.T)), boundary(boundaryVertices(mesh.T)),
        tetsOfVertex(vertexTets(mesh.T, mesh.V.rows())), region(std::size_t(mesh.T.rows()), 0) {}
  long regionTets() const { return long(std::count(region.begin(), region.end(), 1)); }
};

}  // namespace

InterpenetrationReport removeInterpenetration(TetMesh& a, TetMesh& b, const InterpenetrationOptions& o) {
  Side side[2] = {Side(a), Side(b)};
  InterpenetrationReport report;
  for (;;) {
    const std::vector<int> inside[2] = {verticesInside(side[0].V, side[0].boundary, TetLocator(side[1].V, b.T)),
                                        verticesInside(side[1].V, side[1].boundary, TetLocator(side[0].V, a.T))};
    const long count = long(inside[0].size() + inside[1].size());
    if (report.rounds == 0) report.penetratingBefore = count;
    report.penetratingAfter = count;
    if (count == 0 || report.rounds == o.maxRounds) break;
    const double share = inside[0].empty() || inside[1].empty() ? 1.0 : 0.5;
    MatrixX3d targets[2];
    for (int m = 0; m < 2; ++m)
      targets[m] = contactTargets(side[m].V, inside[m], TriangleTree(side[1 - m].V, side[1 - m].F), share, o.clearance);
    for (int m = 0; m < 2; ++m) {
      if (inside[m].empty()) continue;
      growRegion(side[m].T, side[m].tetsOfVertex, inside[m], o.rings, side[m].region);
      side[m].V = pushApart(side[m].V, side[m].T, side[m].region, inside[m], targets[m], o);
    }
    ++report.rounds;
  }
  TetMesh* meshes[2] = {&a, &b};
  for (int m = 0; m < 2; ++m) {
    report.regionTets[m] = side[m].regionTets();
    if (side[m].V.rows() > 0)
      report.maxDisplacement =
          std::max(report.maxDisplacement, (side[m].V - meshes[m]->V).rowwise().norm().maxCoeff());
  }
  a.V = side[0].V;
  b.V = side[1].V;
  return report;
}

std::vector<InterpenetrationReport> removeInterpenetrations(std::vector<TetMesh>& meshes,
                                                            const InterpenetrationOptions& options) {
  std::vector<InterpenetrationReport> reports;
  for (int sweep = 0; sweep < options.maxRounds; ++sweep) {
    long penetrating = 0;
    std::size_t pair = 0;
    for (std::size_t k = 1; k < meshes.size(); ++k)
      for (std::size_t j = 0; j < k; ++j, ++pair) {
        const InterpenetrationReport r = removeInterpenetration(meshes[k], meshes[j], options);
        penetrating += r.penetratingBefore + r.penetratingAfter;
        if (sweep == 0) {
          reports.push_back(r);
          continue;
        }
        InterpenetrationReport& total = reports[pair];
        total.penetratingAfter = r.penetratingAfter;
        total.rounds += r.rounds;
        for (int m = 0; m < 2; ++m) total.regionTets[m] = std::max(total.regionTets[m], r.regionTets[m]);
        total.maxDisplacement = std::max(total.maxDisplacement, r.maxDisplacement);
      }
    if (penetrating == 0) break;
  }
  return reports;
}

}  // namespace vesalius::fit
