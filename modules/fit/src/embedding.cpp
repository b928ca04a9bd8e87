// Surface embedding (embedding.h, Wang et al. 2021, §4.3).
#include "vesalius/fit/embedding.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_embedding.h"

namespace vesalius::fit {

TriMesh embedSurface(const TriMesh& surface, const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& fittedV) {
  if (restV.rows() != fittedV.rows())
    throw UsageError("embedding: rest and fitted positions differ in number of vertices");
  TriMesh moved = surface;
  if (surface.V.rows() > 0) moved.V = embedInTets(restV, T, surface.V).apply(fittedV);
  return moved;
}

}  // namespace vesalius::fit
