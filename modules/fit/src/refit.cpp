// Refits (refit.h): the fit run again from the shape it reached.
#include "vesalius/fit/refit.h"

#include "vesalius/fit/embedding.h"
#include "vesalius/fit/smooth_displacement.h"

#include "vesalius/core/tet_embedding.h"
#include "vesalius/fem/plastic_strain.h"

namespace vesalius::fit {

namespace {

MatrixX3d carried(const MatrixX3d& points, const TetMesh& rest, const MatrixX3d& fittedV) {
  if (points.rows() == 0) return points;
  return embedInTets(rest.V, rest.T, points).apply(fittedV);
}

bool allMarkersClose(const FitResult& r, double maxIcpError) {
  return r.icpErrors.size() == 0 || r.icpErrors.maxCoeff() < maxIcpError;
}

}  // namespace

FitMarkers carriedMarkers(const FitMarkers& markers, const TetMesh& rest, const MatrixX3d& fittedV) {
  FitMarkers next = markers;
  next.templateLandmarks = carried(markers.templateLandmarks, rest, fittedV);
  next.attachmentMaterial = carried(markers.attachmentMaterial, rest, fittedV);
  return next;
}

TriMesh carriedSurface(const TriMesh& surface, const std::vector<FitRound>& rounds) {
  if (rounds.empty()) return surface;
  const FitRound& first = rounds.front();
  TriMesh carried = embedSurface(surface, first.rest.V, first.rest.T, first.result.V);
  for (std::size_t k = 1; k < rounds.size(); ++k) {
    const FitRound& round = rounds[k];
    const MatrixX3d rest = tetBoundarySurface(round.rest.V, round.rest.T).V;
    const MatrixX3d moved = tetBoundarySurface(round.result.V, round.rest.T).V;
    carried.V += smoothDisplacement(carried, rest, moved - rest, Eigen::VectorXd::Ones(rest.rows()));
  }
  return carried;
}

std::vector<FitRound> refit(FitRound first, const FitOptions& fitOptions, const RefitOptions& options,
                            const Remesh& remesh, Progress* progress) {
  std::vector<FitRound> rounds;
  rounds.push_back(std::move(first));
  FitOptions again = fitOptions;
  again.constantStrainIterations = 0;
  again.icpIterations = options.icpIterations;
  for (int k = 0; k < options.refits; ++k) {
    const FitRound& last = rounds.back();
    if (allMarkersClose(last.result, fitOptions.maxIcpError)) break;
    FitRound next;
    next.markers = carriedMarkers(last.markers, last.rest, last.result.V);
    next.rest = remesh(tetBoundarySurface(last.result.V, last.rest.T));
    if (options.maxTets > 0 && next.rest.T.rows() > options.maxTets) break;
    const Eigen::VectorXd s0 = identityPlasticStrain().replicate(next.rest.T.rows(), 1);
    next.result = fitPlasticStrains(next.rest, next.rest.V, s0, next.markers, again, progress);
    const double before = last.result.icpErrors.mean(), after = next.result.icpErrors.mean();
    if (!(after < (1.0 - fitOptions.minIcpGain) * before)) break;
    rounds.push_back(std::move(next));
  }
  return rounds;
}

}  // namespace vesalius::fit
