#include "vesalius/patient/organ_fit.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"
#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fit/initial_placement.h"
#include "vesalius/fit/plastic_fit.h"
#include "vesalius/fit/refit.h"
#include "vesalius/fit/surface_projection.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/meshing/tet_budget.h"

#include <optional>

namespace vesalius::patient {

namespace {

// Marker-to-surface distances of the boundary of tets T at positions V.
Eigen::VectorXd markerErrors(const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& markers) {
  return fit::SurfaceProjection(T).distances(PlasticFem::flatten(V), markers);
}

}  // namespace

OrganFit fitOrganToLabel(const TriMesh& templateSurface, const LabelMap& labels, Label id,
                         const OrganFitOptions& options, const std::string& labelsSource, Progress* progress) {
  const LabelEntry* entry = labels.table.find(id);
  const std::string name = entry ? entry->name : std::to_string(id);
  const std::vector<meshing::LabelSurface> surfaces = meshing::labelSurfaces(labels, {id});
  if (surfaces.empty()) throw BadInput(labelsSource, "label '" + name + "' has no voxels");
  const TriMesh boundary = meshing::withinScan(surfaces.front().mesh, labels.labels.geometry);
  if (boundary.F.rows() == 0)
    throw BadInput(labelsSource, "label '" + name + "' lies wholly on the edge of the scan: no boundary to fit");

  OrganFit out;
  out.markers = meshing::spreadSurfacePoints(boundary, options.markers, options.seed);
  fit::FitMarkers markers;
  markers.icp = out.markers;

  meshing::TetrahedralizeOptions tets;
  tets.targetTets = options.targetTets;
  const TetMesh templ = meshing::tetrahedralizeWithinBudget(templateSurface, tets, name + " template").tets;
  // A label the scan cuts lost its faces on the grid's edge to withinScan: placed by the two-sided ICP.
  std::optional<fit::PlacementView> view;
  if (boundary.F.rows() < surfaces.front().mesh.F.rows())
    view = fit::PlacementView{labels.labels.geometry, boundary};
  const fit::Placement placement = fit::placeTemplate(tetBoundarySurface(templ.V, templ.T), MatrixX3d(0, 3),
                                                      MatrixX3d(0, 3), markers.icp, view ? &*view : nullptr);
  const MatrixX3d x0 = placement.transform.apply(templ.V);
  Eigen::VectorXd s0(6 * templ.T.rows());
  for (Eigen::Index t = 0; t < templ.T.rows(); ++t)
    s0.segment<6>(6 * t) = placement.transform.scale * identityPlasticStrain();
  out.errorBefore = markerErrors(x0, templ.T, markers.icp);

  const fit::FitOptions fitOptions;
  fit::FitRound first{templ, markers, fit::fitPlasticStrains(templ, x0, s0, markers, fitOptions, progress)};
  fit::RefitOptions refit;
  refit.refits = options.refits;
  refit.maxTets = 2 * options.targetTets;
  const std::vector<fit::FitRound> rounds = fit::refit(
      std::move(first), fitOptions, refit,
      [&](const TriMesh& fitted) { return meshing::tetrahedralizeWithinBudget(fitted, tets, name + " refit").tets; },
      progress);
  for (const fit::FitRound& r : rounds) {
    out.tetsPerRound.push_back(r.rest.T.rows());
    out.meanErrorPerRound.push_back(r.result.icpErrors.mean());
  }
  const fit::FitRound& last = rounds.back();
  out.tets.V = last.result.V;
  out.tets.T = last.rest.T;
  out.surface = tetBoundarySurface(out.tets.V, out.tets.T);
  out.errorAfter = last.result.icpErrors;
  out.carriedTemplate = fit::carriedSurface(templateSurface, rounds);
  return out;
}

}  // namespace vesalius::patient
