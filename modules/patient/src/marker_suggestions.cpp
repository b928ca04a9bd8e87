// Marker suggestions (marker_suggestions.h).
#include "vesalius/patient/marker_suggestions.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fit/affine_icp.h"
#include "vesalius/fit/smooth_displacement.h"
#include "vesalius/meshing/surface_samples.h"

#include <algorithm>
#include <cmath>

namespace vesalius::patient {
namespace {

namespace seg = segmentation;

// Outward unit normals of `surface` at points on it: the normal of the closest triangle.
MatrixX3d normalsAt(const TriMesh& surface, const MatrixX3d& points) {
  const TriangleTree tree(surface.V, surface.F);
  const std::vector<ClosestPoint> closest = tree.closest(points);
  MatrixX3d N(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3i f = surface.F.row(closest[std::size_t(i)].face).transpose();
    const Eigen::Vector3d a = surface.V.row(f[0]), b = surface.V.row(f[1]), c = surface.V.row(f[2]);
    N.row(i) = (b - a).cross(c - a).normalized().transpose();
  }
  return N;
}

// Edges along the normals of `placed` at `count` points spread over its part within the scan.
struct Search {
  MatrixX3d candidates;
  seg::NormalEdges found;
  double area = 0;  // mm², of the placed surface within the scan
};

Search searchEdges(const Image& scan, const TriMesh& placed, int count, double searchMm,
                   const MarkerSuggestionOptions& o) {
  const TriMesh inScan = meshing::withinScan(placed, scan.geometry);
  if (inScan.F.rows() == 0) throw BadInput(o.templateName, "placed on the scan, no triangle lies within it");
  Search s;
  s.candidates = meshing::spreadSurfacePoints(inScan, count, o.seed);
  s.found = seg::findNormalEdges(scan, s.candidates, normalsAt(placed, s.candidates),
                                 {o.sigmaMm, searchMm, 0.25, o.polarity});
  s.area = triangleAreas(inScan.V, inScan.F).sum();
  return s;
}

// The active-shape rounds (step 2 of the header).
TriMesh bendOntoEdges(const Image& scan, TriMesh placed, const MarkerSuggestionOptions& o) {
  for (int r = 0; r < o.rounds; ++r) {
    const double searchMm = o.searchMm * std::pow(o.finalSearchMm / o.searchMm, double(r) / o.rounds);
    const Search s = searchEdges(scan, placed, o.roundPoints, searchMm, o);
    MatrixX3d moves(s.candidates.rows(), 3);
    Eigen::VectorXd weights(s.candidates.rows());
    for (Eigen::Index i = 0; i < s.candidates.rows(); ++i) {
      const seg::NormalEdge& e = s.found.edges[std::size_t(i)];
      moves.row(i) = (e.position - s.candidates.row(i).transpose()).transpose();
      weights[i] = e.found ? e.confidence : 0.0;
    }
    placed.V += fit::smoothDisplacement(placed, s.candidates, moves, weights, {o.smoothness});
  }
  return placed;
}

// Up to `count` found edges, most confident first, each at least `spacing` mm from those kept before it
// (so a stretch of strong edge does not take every suggestion); then, if fewer were kept, the most
// confident of the rest.
std::vector<std::size_t> pickSpread(const std::vector<seg::NormalEdge>& edges, int count, double spacing) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (edges[i].found) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return edges[a].confidence > edges[b].confidence; });
  std::vector<std::size_t> kept, rest;
  for (std::size_t i : order) {
    const bool apart = std::all_of(kept.begin(), kept.end(), [&](std::size_t k) {
      return (edges[i].position - edges[k].position).norm() >= spacing;
    });
    (apart && int(kept.size()) < count ? kept : rest).push_back(i);
  }
  for (std::size_t i = 0; i < rest.size() && int(kept.size()) < count; ++i) kept.push_back(rest[i]);
  return kept;
}

}  // namespace

MarkerSuggestions suggestMarkers(const Image& scan, const TriMesh& templ, const MatrixX3d& targets,
                                 const MarkerSuggestionOptions& o) {
  MarkerSuggestions result;
  StageClock clock(result.stageSeconds);
  result.placement = fit::placeTemplate(templ, MatrixX3d(0, 3), MatrixX3d(0, 3), targets);
  result.placed = templ;
  result.placed.V = result.placement.transform.apply(templ.V);
  result.placed = fit::refineAffineIcp(result.placed, targets);
  clock.end("placement");
  result.placed = bendOntoEdges(scan, result.placed, o);
  Search last = searchEdges(scan, result.placed, o.count * o.candidatesPerSuggestion,
                            o.rounds > 0 ? o.finalSearchMm : o.searchMm, o);
  clock.end("bending and edge search");
  result.kept = pickSpread(last.found.edges, o.count, 0.5 * std::sqrt(last.area / o.count));
  result.found = std::move(last.found);
  result.area = last.area;
  return result;
}

}  // namespace vesalius::patient
