#include "vesalius/meshing/tet_budget.h"

#include "vesalius/core/error.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/meshing/closed_surface.h"
#include "vesalius/meshing/decimate_surface.h"

#include <algorithm>

namespace vesalius::meshing {

namespace {

// Below facesForTets' 200 triangles, decimation costs the shape more than TetGen's refinement costs tets:
// the liver template fitted on the shipped MRI at a target of 2,000 tets reached Dice 0.74 with its label
// from a 100-triangle surface, 0.93 from 200. So at 200 the quality bound is first relaxed to TetGen's own
// default radius-edge ratio (that liver: 4,130 tets at 1.5, 3,218 at 2.0), and only then is the surface
// halved further, to 50 triangles at the fewest.
constexpr int kFewFaces = 200;
constexpr int kFewestFaces = 50;
constexpr double kRelaxedRadiusEdge = 2.0;

struct Coarsened {
  BudgetedTets tets;
  TriMesh surface;  // what TetGen was given
};

// `surface` decimated to `faces` triangles, then halved (not below `fewest`) while the tets are more than
// twice the target; the attempt with the fewest tets. coarsenings counts on from `coarsenings`.
Coarsened halvedWhileOverBudget(const TriMesh& surface, const TetrahedralizeOptions& options, int faces, int fewest,
                                int coarsenings, const std::string& source) {
  Coarsened best;
  for (;;) {
    const TriMesh coarse = coarsenedSurface(surface, faces);
    // Halving stops where decimation can no longer take faces off (a surface of many small parts): a
    // surface no coarser than the last would only give more tets.
    if (best.tets.tets.T.rows() > 0 && coarse.F.rows() >= best.tets.surfaceFaces) break;
    TetMesh tets = tetrahedralize(coarse, options, source);
    if (coarse.F.rows() < surface.F.rows()) ++coarsenings;
    if (best.tets.tets.T.rows() == 0 || tets.T.rows() < best.tets.tets.T.rows()) {
      best.tets.tets = std::move(tets);
      best.tets.surfaceFaces = coarse.F.rows();
      best.tets.coarsenings = coarsenings;
      best.surface = coarse;
    }
    if (best.tets.tets.T.rows() <= 2 * options.targetTets || coarse.F.rows() <= fewest || faces <= fewest ||
        coarse.F.rows() > faces * 2)
      break;
    faces = std::max<int>(fewest, int(std::min<long>(faces, coarse.F.rows())) / 2);
  }
  return best;
}

}  // namespace

int facesForTets(long targetTets) { return int(std::max<long>(kFewFaces, targetTets / 10)); }

TriMesh coarsenedSurface(const TriMesh& surface, int faces) {
  TriMesh coarse = decimateSurface(surface, faces);
  if (selfIntersections(coarse.V, coarse.F).empty()) return coarse;
  ClosedSurfaceOptions closing;
  closing.targetFaces = faces;
  return closedSurface(surface, closing);
}

BudgetedTets tetrahedralizeWithinBudget(const TriMesh& surface, const TetrahedralizeOptions& options,
                                        const std::string& source) {
  if (options.targetTets <= 0) throw UsageError("tetrahedralize within a budget: the tet target must be positive");
  Coarsened coarsened =
      halvedWhileOverBudget(surface, options, facesForTets(options.targetTets), kFewFaces, 0, source);
  if (coarsened.tets.tets.T.rows() > 2 * options.targetTets && coarsened.tets.surfaceFaces <= kFewFaces &&
      options.radiusEdge > 0 && options.radiusEdge < kRelaxedRadiusEdge) {
    TetrahedralizeOptions relaxed = options;
    relaxed.radiusEdge = kRelaxedRadiusEdge;
    // From the same surface again: its decimation is not counted twice.
    const int before = coarsened.tets.coarsenings - (coarsened.tets.surfaceFaces < surface.F.rows() ? 1 : 0);
    Coarsened fewer = halvedWhileOverBudget(surface, relaxed, int(coarsened.tets.surfaceFaces), kFewestFaces,
                                            before, source);
    if (fewer.tets.tets.T.rows() < coarsened.tets.tets.T.rows()) coarsened = std::move(fewer);
  }
  BudgetedTets best = std::move(coarsened.tets);
  const TriMesh& bestSurface = coarsened.surface;
  if (best.tets.T.rows() <= 2 * options.targetTets || options.keepSurface || !options.keepSurfaceOverBudget) return best;
  TetrahedralizeOptions kept = options;
  kept.keepSurface = true;
  try {
    TetMesh tets = tetrahedralize(bestSurface, kept, source);
    if (tets.T.rows() < best.tets.T.rows()) {
      best.tets = std::move(tets);
      best.surfaceKept = true;
    }
  } catch (const BadInput&) {
    // Kept as given, a surface whose triangles are far from the quality bound can need more interior points
    // than the budget allows (a fitted liver): the tets refining the surface stay.
  }
  return best;
}

}  // namespace vesalius::meshing
