// Points carried by a tet mesh (tet_embedding.h).
#include "vesalius/core/tet_embedding.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <string>
#include <vector>

namespace vesalius {

TetEmbedding embedInTets(const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& P) {
  const TetLocator locator(V, T);
  const std::vector<TetLocation> where = locator.locateOrNearest(P);
  TetEmbedding e{Eigen::VectorXi(P.rows()), MatrixX4i(P.rows(), 4), Eigen::Matrix<double, Eigen::Dynamic, 4>(P.rows(), 4)};
  tbb::parallel_for(Eigen::Index(0), P.rows(), [&](Eigen::Index p) {
    const int t = where[std::size_t(p)].tet;
    e.tet[p] = t;
    e.corners.row(p) = T.row(t);
    // Inside, this equals the locator's weights; outside, it is the tet's affine extension (see header).
    e.barycentric.row(p) = locator.barycentric(t, P.row(p).transpose()).transpose();
  });
  return e;
}

MatrixX3d TetEmbedding::apply(const MatrixX3d& deformedV) const {
  if (corners.size() > 0 && corners.maxCoeff() >= deformedV.rows())
    throw UsageError("tet embedding: a tet corner is beyond the " + std::to_string(deformedV.rows()) +
                     " deformed vertices");
  MatrixX3d carried(corners.rows(), 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, carried.rows(), 4096), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index p = r.begin(); p < r.end(); ++p) {
      Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
      for (int k = 0; k < 4; ++k) x += barycentric(p, k) * deformedV.row(corners(p, k));
      carried.row(p) = x;
    }
  });
  return carried;
}

}  // namespace vesalius
