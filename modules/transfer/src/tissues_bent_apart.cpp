// Tissues bent out of the tissues they reach into (tissues_bent_apart.h).
#include "vesalius/transfer/tissues_bent_apart.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/meshing/winding_number.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace vesalius::transfer {

namespace {

// The vertices of `mesh`, then its edges' midpoints and its faces' centroids.
MatrixX3d surfacePoints(const TriMesh& mesh) {
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) edges.emplace(std::minmax(mesh.F(f, k), mesh.F(f, (k + 1) % 3)));
  MatrixX3d P(mesh.V.rows() + Eigen::Index(edges.size()) + mesh.F.rows(), 3);
  P.topRows(mesh.V.rows()) = mesh.V;
  Eigen::Index r = mesh.V.rows();
  for (const auto& [a, b] : edges) P.row(r++) = (mesh.V.row(a) + mesh.V.row(b)) / 2;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    P.row(r++) = (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) + mesh.V.row(mesh.F(f, 2))) / 3;
  return P;
}

// A bent tissue: its rows in the measured points (its vertices first, then surfacePoints' others) and its
// triangles.
struct BentTissue {
  Eigen::Index first = 0, vertices = 0, rows = 0;
  const MatrixX3i* F = nullptr;
};

// A fixed tissue: its box and vertex normals.
struct FixedTissue {
  const TriMesh* mesh = nullptr;
  Eigen::AlignedBox3d box;
  MatrixX3d normals;
};

// The distances warpIntoSkin takes (the header's three cases, the largest), the skin's signed distance
// where none applies.
SkinDistanceFunction reachingIn(const std::vector<FixedTissue>& fixed, const std::vector<BentTissue>& bent,
                                const SkinDistanceFunction& skin, const StraddleOptions& straddle) {
  const auto deepen = [](SkinDistances& d, Eigen::Index r, double depth, const Eigen::RowVector3d& outward) {
    if (depth <= d.distance[r]) return;
    d.distance[r] = depth;
    d.outward.row(r) = outward;
  };
  const auto counts = [fov = straddle.fieldOfView](const Eigen::Vector3d& p) { return !fov || fov->seesPoint(p); };
  return [fixed, bent, skin, deepen, rule = straddle.rule, counts](const MatrixX3d& P) {
    SkinDistances d = skin(P);
    for (const FixedTissue& f : fixed) {
      std::vector<Eigen::Index> rows;
      for (Eigen::Index r = 0; r < P.rows(); ++r)
        if (f.box.contains(P.row(r).transpose())) rows.push_back(r);
      if (rows.empty()) continue;
      for (const meshing::PointInside& in : meshing::pointsInside(f.mesh->V, f.mesh->F, MatrixX3d(P(rows, Eigen::all)))) {
        const Eigen::Index r = rows[std::size_t(in.row)];
        const Eigen::RowVector3d deeper = P.row(r) - in.closest.point.transpose();
        if (deeper.norm() > 1e-9) deepen(d, r, deeper.norm(), deeper.normalized());
      }
    }
    for (const BentTissue& t : bent) {
      const MatrixX3d V = P.middleRows(t.first, t.vertices);
      const Eigen::AlignedBox3d box = boundingBox(V);
      // The fixed tissues' vertices in the bent tissue's box, tested against one tree of it.
      std::vector<std::pair<const FixedTissue*, Eigen::Index>> near;
      for (const FixedTissue& f : fixed) {
        if (!f.box.intersects(box)) continue;
        for (Eigen::Index v = 0; v < f.mesh->V.rows(); ++v)
          if (box.contains(f.mesh->V.row(v).transpose()) && counts(f.mesh->V.row(v).transpose())) near.emplace_back(&f, v);
      }
      if (near.empty()) continue;
      MatrixX3d Q(Eigen::Index(near.size()), 3);
      for (std::size_t k = 0; k < near.size(); ++k) Q.row(Eigen::Index(k)) = near[k].first->mesh->V.row(near[k].second);
      for (const meshing::PointInside& in : meshing::pointsInside(V, *t.F, Q)) {
        const FixedTissue& f = *near[std::size_t(in.row)].first;
        const Eigen::Index v = near[std::size_t(in.row)].second;
        Eigen::Index nearest = 0;
        if (rule == Straddle::MoveOff) {
          (P.middleRows(t.first, t.rows).rowwise() - f.mesh->V.row(v)).rowwise().squaredNorm().minCoeff(&nearest);
          deepen(d, t.first + nearest, std::sqrt(in.closest.squaredDistance), -f.normals.row(v));
        } else {
          const Eigen::RowVector3d closest = in.closest.point.transpose(), outward = closest - f.mesh->V.row(v);
          if (outward.norm() < 1e-9) continue;
          (P.middleRows(t.first, t.rows).rowwise() - closest).rowwise().squaredNorm().minCoeff(&nearest);
          deepen(d, t.first + nearest, outward.norm(), outward.normalized());
        }
      }
    }
    return d;
  };
}

}  // namespace

TissuesBentApart bendTissuesApart(ReferenceAnatomy& anatomy, const std::vector<BendRole>& roles,
                                  const SkinDistanceFunction& skin, const InsideSkinWarpOptions& options,
                                  const StraddleOptions& straddle) {
  std::vector<ReferenceTissue>& tissues = anatomy.tissues;
  if (roles.size() != tissues.size()) throw UsageError("bendTissuesApart: one role per tissue is needed");
  std::vector<FixedTissue> fixed;
  for (std::size_t t = 0; t < tissues.size(); ++t)
    if (roles[t] == BendRole::Fixed && tissues[t].mesh.F.rows() > 0)
      fixed.push_back({&tissues[t].mesh, boundingBox(tissues[t].mesh.V), vertexNormals(tissues[t].mesh.V, tissues[t].mesh.F)});
  std::vector<BentTissue> bent;
  MatrixX3d P(0, 3);
  for (std::size_t t = 0; t < tissues.size(); ++t) {
    const TriMesh& mesh = tissues[t].mesh;
    if (roles[t] != BendRole::Bent || mesh.F.rows() == 0) continue;
    const Eigen::AlignedBox3d box = boundingBox(mesh.V);
    if (std::none_of(fixed.begin(), fixed.end(), [&](const FixedTissue& f) { return f.box.intersects(box); })) continue;
    const MatrixX3d points = surfacePoints(mesh);
    bent.push_back({P.rows(), mesh.V.rows(), points.rows(), &mesh.F});
    P.conservativeResize(P.rows() + points.rows(), 3);
    P.bottomRows(points.rows()) = points;
  }
  TissuesBentApart result;
  if (P.rows() == 0 || options.rounds == 0) return result;
  result.bend = warpIntoSkin(P, reachingIn(fixed, bent, skin, straddle), options);
  const InsideSkinWarp& bend = result.bend;
  result.insideBefore = bend.outsideBefore;
  result.insideAfter = bend.outsideAfter;
  result.largestMoveMm = bend.largestMoveMm;
  if (bend.centres.empty()) return result;
  // The bend is zero beyond the reach of every centre.
  Eigen::AlignedBox3d reach;
  for (std::size_t r = 0; r < bend.centres.size(); ++r) {
    const Eigen::AlignedBox3d b = boundingBox(bend.centres[r]);
    reach.extend(b.min() - Eigen::Vector3d::Constant(bend.radiiMm[r]));
    reach.extend(b.max() + Eigen::Vector3d::Constant(bend.radiiMm[r]));
  }
  std::vector<std::string> moved;
  for (std::size_t t = 0; t < tissues.size(); ++t) {
    if (roles[t] != BendRole::Bent || tissues[t].mesh.V.rows() == 0 || !boundingBox(tissues[t].mesh.V).intersects(reach)) continue;
    tissues[t].mesh.V = bend.apply(tissues[t].mesh.V);
    moved.push_back(tissues[t].name);
  }
  for (ReferencePoint& p : anatomy.points)
    if (std::find(moved.begin(), moved.end(), p.tissue) != moved.end())
      p.position = bend.apply(p.position.transpose()).transpose();
  return result;
}

}  // namespace vesalius::transfer
