#include "vesalius/fit/initial_placement.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include "vesalius/core/principal_axes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

namespace vesalius::fit {
namespace {

// Whether `p` lies within half a voxel of the voxel centres' box of `grid`.
bool insideGrid(const GridGeometry& grid, const Eigen::Vector3d& p) {
  const Eigen::Vector3d index = grid.worldToIndex(p);
  for (int a = 0; a < 3; ++a)
    if (!(index[a] >= -0.5 && index[a] <= grid.size[a] - 0.5)) return false;
  return true;
}

// The view's surface for closest-point queries. Its open rim is where the scan cuts the organ: a template
// vertex whose closest point lies on the rim has no partner on the organ (it is at or beyond the cut).
class ViewTarget {
 public:
  explicit ViewTarget(const PlacementView& view) : grid_(view.grid), tree_(view.surface.V, view.surface.F) {
    const MatrixX3i& F = view.surface.F;
    std::map<std::pair<int, int>, int> uses;
    const auto edge = [&](Eigen::Index f, int j) {
      const int a = F(f, (j + 1) % 3), b = F(f, (j + 2) % 3);
      return std::make_pair(std::min(a, b), std::max(a, b));
    };
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j) ++uses[edge(f, j)];
    rim_.resize(std::size_t(F.rows()));
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int j = 0; j < 3; ++j) rim_[std::size_t(f)][std::size_t(j)] = uses[edge(f, j)] == 1;
  }
  const GridGeometry& grid() const { return grid_; }
  std::vector<ClosestPoint> closest(const MatrixX3d& P) const { return tree_.closest(P); }
  // Whether `hit` lies on an edge of the rim (its weight of the opposite corner is 0).
  bool onRim(const ClosestPoint& hit) const {
    for (int j = 0; j < 3; ++j)
      if (rim_[std::size_t(hit.face)][std::size_t(j)] && hit.barycentric[j] < 1e-9) return true;
    return false;
  }

 private:
  GridGeometry grid_;
  TriangleTree tree_;
  std::vector<std::array<bool, 3>> rim_;  // per face, whether the edge opposite each corner is open
};

// Similarity ICP from `start`: markers pulled to their closest surface points and, with a view, the
// surface's vertices inside the scan to their closest points of the view's surface off its rim, each set
// weighing half; the similarity refitted to those pairs, until the RMS distance stops improving.
// `templateTree` holds `surface` in template space, where the markers are taken back to (distances scale
// with the transform). Point-to-point ICP creeps along the directions a cut leaves free, hence the
// thousand iterations at most.
Placement icpFrom(const TriMesh& surface, const TriangleTree& templateTree, const MatrixX3d& icp,
                  const SimilarityTransform& start, const ViewTarget* view) {
  Placement best{start, std::numeric_limits<double>::infinity(), 0};
  SimilarityTransform current = start;
  for (int it = 0; it < 1000; ++it) {
    const MatrixX3d back = ((icp.rowwise() - current.translation.transpose()) * current.rotation) / current.scale;
    std::vector<ClosestPoint> hits = templateTree.closest(back);
    for (ClosestPoint& h : hits) h.squaredDistance *= current.scale * current.scale;
    std::vector<Eigen::Index> inside;
    const MatrixX3d placed = view ? current.apply(surface.V) : MatrixX3d();
    for (Eigen::Index v = 0; v < placed.rows(); ++v)
      if (insideGrid(view->grid(), placed.row(v).transpose())) inside.push_back(v);
    std::vector<ClosestPoint> viewHits;
    if (!inside.empty()) {
      MatrixX3d queries(Eigen::Index(inside.size()), 3);
      for (std::size_t k = 0; k < inside.size(); ++k) queries.row(Eigen::Index(k)) = placed.row(inside[k]);
      viewHits = view->closest(queries);
    }
    std::vector<std::size_t> paired;
    for (std::size_t k = 0; k < viewHits.size(); ++k)
      if (!view->onRim(viewHits[k])) paired.push_back(k);
    const Eigen::Index markers = icp.rows(), n = markers + Eigen::Index(paired.size());
    MatrixX3d material(n, 3), target(n, 3);
    Eigen::VectorXd weights = Eigen::VectorXd::Constant(n, 1.0 / double(markers));
    double markerSum = 0, viewSum = 0;
    for (Eigen::Index i = 0; i < markers; ++i) {
      const ClosestPoint& h = hits[std::size_t(i)];
      material.row(i) = h.point.transpose();
      target.row(i) = icp.row(i);
      markerSum += h.squaredDistance;
    }
    for (std::size_t k = 0; k < paired.size(); ++k) {
      const Eigen::Index row = markers + Eigen::Index(k);
      const ClosestPoint& h = viewHits[paired[k]];
      material.row(row) = surface.V.row(inside[paired[k]]);
      target.row(row) = h.point.transpose();
      weights(row) = 1.0 / double(paired.size());
      viewSum += h.squaredDistance;
    }
    const double markerMean = markerSum / double(markers);
    const double rms =
        std::sqrt(paired.empty() ? markerMean : 0.5 * (markerMean + viewSum / double(paired.size())));
    if (rms > best.rmsError * (1 - 1e-6)) break;
    best = {current, rms, it};
    current = fitSimilarity(material, target, weights, true);
  }
  return best;
}

}  // namespace

Placement placeTemplate(const TriMesh& surface, const MatrixX3d& templateLandmarks, const MatrixX3d& scanLandmarks,
                        const MatrixX3d& icp, const PlacementView* view) {
  if (templateLandmarks.rows() >= 3) {
    Placement p;
    p.transform = fitSimilarity(templateLandmarks, scanLandmarks, Eigen::VectorXd(), true);
    p.rmsError = std::sqrt((p.transform.apply(templateLandmarks) - scanLandmarks).rowwise().squaredNorm().mean());
    return p;
  }
  if (icp.rows() < 3) throw BadInput("", "placing the template needs 3 landmark pairs or 3 ICP markers");
  const PrincipalAxes from = principalAxes(surface.V), to = principalAxes(icp);
  const TriangleTree templateTree(surface.V, surface.F);
  std::vector<SimilarityTransform> starts;
  for (const Eigen::Vector3d& signs : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(-1, -1, 1),
                                      Eigen::Vector3d(-1, 1, -1), Eigen::Vector3d(1, -1, -1)}) {
    SimilarityTransform start;
    start.rotation = to.axes * signs.asDiagonal() * from.axes.transpose();
    start.scale = std::sqrt(to.variances.sum() / from.variances.sum());
    start.translation = to.centroid - start.scale * start.rotation * from.centroid;
    starts.push_back(start);
  }
  const auto bestFrom = [&](const std::vector<SimilarityTransform>& candidates, const ViewTarget* v) {
    Placement best;
    best.rmsError = std::numeric_limits<double>::infinity();
    for (const SimilarityTransform& start : candidates) {
      const Placement p = icpFrom(surface, templateTree, icp, start, v);
      if (p.rmsError < best.rmsError) best = p;
    }
    return best;
  };
  const Placement markersAlone = bestFrom(starts, nullptr);
  if (!view || view->surface.F.rows() == 0) return markersAlone;
  // Two-sided from the same starts, from the markers' own placement (which sits on the visible part) and
  // from the template as it is turned, at that placement's scale and above it.
  const ViewTarget target(*view);
  starts.push_back(markersAlone.transform);
  for (double f : {1.0, 1.3}) {
    SimilarityTransform start;
    start.scale = markersAlone.transform.scale * f;
    start.translation = to.centroid - start.scale * from.centroid;
    starts.push_back(start);
  }
  return bestFrom(starts, &target);
}

}  // namespace vesalius::fit
