#include "vesalius/meshing/template_tets.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/meshing/closed_surface.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vesalius::meshing {

namespace {

void refuseFlat(const TriMesh& surface, const std::string& source) {
  if (surface.V.rows() == 0) return;  // the tetrahedralization reports an empty mesh
  const double diagonal = (surface.V.colwise().maxCoeff() - surface.V.colwise().minCoeff()).norm();
  // Thickness across its flattest direction: the root of the smallest variance of the vertices.
  const MatrixX3d centred = surface.V.rowwise() - surface.V.colwise().mean();
  const Eigen::Matrix3d covariance = centred.transpose() * centred / double(surface.V.rows());
  const double thickness =
      std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues()(0)));
  if (thickness <= 1e-6 * diagonal) {
    std::ostringstream text;
    text << "the template's vertices lie in one plane (" << thickness << " mm thick, " << diagonal
         << " mm across): a flat surface has no inside to fill with tets";
    throw BadInput(source, text.str());
  }
  const double volume = std::abs(enclosedVolume(surface.V, surface.F));
  if (volume <= 1e-6 * diagonal * diagonal * diagonal) {
    std::ostringstream text;
    text << "the template encloses " << volume << " mm^3 inside a bounding box " << diagonal
         << " mm across: a flat surface has no inside to fill with tets";
    throw BadInput(source, text.str());
  }
}

}  // namespace

BudgetedTets closedSurfaceTets(const TriMesh& surface, const TemplateTetsOptions& options, const std::string& source) {
  TetrahedralizeOptions tetgen;
  tetgen.targetTets = options.targetTets;
  if (options.faces <= 0) return tetrahedralizeWithinBudget(surface, tetgen, source);
  if (options.targetTets <= 0) throw UsageError("tetrahedralize a surface: the tet target must be positive");
  const TriMesh coarse = coarsenedSurface(surface, options.faces);
  BudgetedTets result;
  result.tets = tetrahedralize(coarse, tetgen, source);
  result.surfaceFaces = coarse.F.rows();
  result.coarsenings = coarse.F.rows() < surface.F.rows() ? 1 : 0;
  return result;
}

TemplateTets templateTets(const TriMesh& surface, const TemplateTetsOptions& options, const std::string& source) {
  TemplateTets result;
  result.surface = surface;
  refuseFlat(surface, source);  // before closing: the winding number of a flat surface is noise
  const EdgeCounts edges = countEdges(surface.F);
  const std::size_t crossings = surface.F.rows() ? selfIntersections(surface.V, surface.F).size() : 0;
  if (edges.boundary != 0 || edges.nonManifold != 0 || crossings != 0) {
    ClosedSurfaceOptions closing;
    closing.targetFaces = options.faces > 0 ? options.faces : int(surface.F.rows());
    try {
      result.surface = closedSurface(surface, closing);
    } catch (const BadInput& e) {
      throw BadInput(source, e.problem());
    }
    result.repair = SurfaceRepair{edges.boundary, edges.nonManifold, long(crossings), long(result.surface.F.rows())};
    refuseFlat(result.surface, source);
  }
  const BudgetedTets tets = closedSurfaceTets(result.surface, options, source);
  result.tets = tets.tets;
  result.tetrahedralizedFaces = tets.surfaceFaces;
  return result;
}

}  // namespace vesalius::meshing
