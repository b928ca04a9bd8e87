// Surface embedding (embedding.h, seed 002 §4.3).
#include "vesalius/fit/embedding.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"

#include <vector>

namespace vesalius::fit {

TriMesh embedSurface(const TriMesh& surface, const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& fittedV) {
  if (restV.rows() != fittedV.rows())
    throw UsageError("embedding: rest and fitted positions differ in number of vertices");
  TriMesh moved = surface;
  if (surface.V.rows() == 0) return moved;
  const TetLocator locator(restV, T);
  const std::vector<TetLocation> where = locator.locateOrNearest(surface.V);
  for (Eigen::Index v = 0; v < surface.V.rows(); ++v) {
    const int tet = where[std::size_t(v)].tet;
    const Eigen::Vector4d weights = locator.barycentric(tet, surface.V.row(v).transpose());
    moved.V.row(v).setZero();
    for (int corner = 0; corner < 4; ++corner) moved.V.row(v) += weights[corner] * fittedV.row(T(tet, corner));
  }
  return moved;
}

}  // namespace vesalius::fit
