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
  BudgetedTets result;
  int faces = facesForTets(options.targetTets);
  for (;;) {
    const TriMesh coarse = coarsenedSurface(surface, faces);
    result.tets = tetrahedralize(coarse, options, source);
    result.surfaceFaces = coarse.F.rows();
    if (coarse.F.rows() < surface.F.rows()) ++result.coarsenings;
    // Halving stops where decimation can no longer take faces off (a surface of many small parts).
    if (result.tets.T.rows() <= 2 * options.targetTets || coarse.F.rows() <= 200 || faces <= 200 ||
        coarse.F.rows() > faces * 2)
      return result;
    faces = std::max<int>(200, int(std::min<long>(faces, coarse.F.rows())) / 2);
  }
}

}  // namespace vesalius::meshing
