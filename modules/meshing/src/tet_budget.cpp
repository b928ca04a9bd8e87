#include "vesalius/meshing/tet_budget.h"

#include "vesalius/core/error.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/meshing/closed_surface.h"
#include "vesalius/meshing/decimate_surface.h"

#include <algorithm>

namespace vesalius::meshing {

int facesForTets(long targetTets) { return int(std::max<long>(200, targetTets / 10)); }

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
  BudgetedTets best;
  TriMesh bestSurface;
  int faces = facesForTets(options.targetTets), coarsenings = 0;
  for (;;) {
    const TriMesh coarse = coarsenedSurface(surface, faces);
    // Halving stops where decimation can no longer take faces off (a surface of many small parts): a
    // surface no coarser than the last would only give more tets.
    if (best.tets.T.rows() > 0 && coarse.F.rows() >= best.surfaceFaces) break;
    TetMesh tets = tetrahedralize(coarse, options, source);
    if (coarse.F.rows() < surface.F.rows()) ++coarsenings;
    if (best.tets.T.rows() == 0 || tets.T.rows() < best.tets.T.rows()) {
      best.tets = std::move(tets);
      best.surfaceFaces = coarse.F.rows();
      best.coarsenings = coarsenings;
      bestSurface = coarse;
    }
    if (best.tets.T.rows() <= 2 * options.targetTets || coarse.F.rows() <= 200 || faces <= 200 ||
        coarse.F.rows() > faces * 2)
      break;
    faces = std::max<int>(200, int(std::min<long>(faces, coarse.F.rows())) / 2);
  }
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
