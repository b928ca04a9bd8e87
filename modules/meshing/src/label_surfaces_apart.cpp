// Label surfaces of one label map moved apart where they cross (label_surfaces_apart.h).
#include "vesalius/meshing/label_surfaces_apart.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/meshing/winding_number.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace vesalius::meshing {

namespace {

struct Crossing {
  long inside = 0;
  double deepestMm = 0;
  std::vector<MatrixX3d> moves;  // per surface, #V by 3
};

// Every seen vertex of every surface inside another, and the move that takes it half way out (all the way
// out of a fixed surface; a fixed surface's vertices do not move).
Crossing crossings(const std::vector<TriMesh*>& surfaces, const std::vector<std::vector<bool>>& seen,
                   const std::vector<bool>& fixed, double marginMm) {
  Crossing c;
  std::vector<Eigen::AlignedBox3d> boxes;
  for (const TriMesh* s : surfaces) {
    boxes.push_back(boundingBox(s->V));
    c.moves.push_back(MatrixX3d::Zero(s->V.rows(), 3));
  }
  for (std::size_t i = 0; i < surfaces.size(); ++i)
    for (std::size_t j = 0; j < surfaces.size(); ++j) {
      if (i == j || fixed[i] || !boxes[i].intersects(boxes[j]) || surfaces[j]->F.rows() == 0) continue;
      const double share = fixed[j] ? 1.0 : 0.5;
      std::vector<Eigen::Index> rows;
      for (Eigen::Index v = 0; v < surfaces[i]->V.rows(); ++v)
        if (seen[i][std::size_t(v)] && boxes[j].contains(surfaces[i]->V.row(v).transpose())) rows.push_back(v);
      if (rows.empty()) continue;
      const MatrixX3d points = surfaces[i]->V(rows, Eigen::all);
      for (const PointInside& in : pointsInside(surfaces[j]->V, surfaces[j]->F, points)) {
        const double depth = std::sqrt(in.closest.squaredDistance);
        if (depth < 1e-9) continue;  // on the other surface
        const Eigen::Index v = rows[std::size_t(in.row)];
        ++c.inside;
        c.deepestMm = std::max(c.deepestMm, depth);
        const Eigen::RowVector3d out =
            (in.closest.point.transpose() - surfaces[i]->V.row(v)) / depth * (depth + marginMm) * share;
        if (out.squaredNorm() > c.moves[i].row(v).squaredNorm()) c.moves[i].row(v) = out;
      }
    }
  return c;
}

}  // namespace

LabelSurfacesApart moveLabelSurfacesApart(const std::vector<TriMesh*>& surfaces, const GridGeometry* fieldOfView,
                                          const LabelSurfacesApartOptions& options) {
  if (!(options.marginMm >= 0 && options.rounds >= 0) ||
      !(options.fixed.empty() || options.fixed.size() == surfaces.size()))
    throw UsageError("moveLabelSurfacesApart: options out of range");
  const std::vector<bool> fixed = options.fixed.empty() ? std::vector<bool>(surfaces.size(), false) : options.fixed;
  std::vector<std::vector<bool>> seen;
  std::vector<MatrixX3d> start;
  for (const TriMesh* s : surfaces) {
    if (!s) throw UsageError("moveLabelSurfacesApart: a surface is null");
    std::vector<bool> sees(std::size_t(s->V.rows()));
    for (Eigen::Index v = 0; v < s->V.rows(); ++v)
      sees[std::size_t(v)] = !fieldOfView || fieldOfView->seesPoint(s->V.row(v).transpose());
    seen.push_back(std::move(sees));
    start.push_back(s->V);
  }
  LabelSurfacesApart result;
  Crossing c = crossings(surfaces, seen, fixed, options.marginMm);
  result.insideBefore = c.inside;
  result.deepestBeforeMm = c.deepestMm;
  for (int round = 0; round < options.rounds && c.inside > 0; ++round) {
    for (std::size_t i = 0; i < surfaces.size(); ++i) surfaces[i]->V += c.moves[i];
    ++result.rounds;
    c = crossings(surfaces, seen, fixed, options.marginMm);
  }
  result.insideAfter = c.inside;
  result.deepestAfterMm = c.deepestMm;
  for (std::size_t i = 0; i < surfaces.size(); ++i)
    if (surfaces[i]->V.rows() > 0)
      result.largestMoveMm = std::max(result.largestMoveMm, (surfaces[i]->V - start[i]).rowwise().norm().maxCoeff());
  return result;
}

}  // namespace vesalius::meshing
