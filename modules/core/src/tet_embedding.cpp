// Points carried by a tet mesh (tet_embedding.h).
#include "vesalius/core/tet_embedding.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <string>
#include <vector>

namespace vesalius {

TetEmbedding embedInTets(const MatrixX3d& V, const MatrixX4i& T, const MatrixX3d& P) {
  const TetLocator locator(V, T);
  const std::vector<TetLocation> where = locator.locateOrNearest(P);
  TetEmbedding e{Eigen::VectorXi(P.rows()), MatrixX4i(P.rows(), 4),
                 Eigen::Matrix<double, Eigen::Dynamic, 4>(P.rows(), 4)};
  tbb::parallel_for(Eigen::Index(0), P.rows(), [&](Eigen::Index p) {
    const TetLocation& at = where[std::size_t(p)];
    e.tet[p] = at.tet;
    e.corners.row(p) = T.row(at.tet);
    // Inside, the locator's weights are barycentric(tet, p); outside, take the tet's affine extension (see
    // header) in place of the clamped weights.
    const Eigen::Vector4d w = at.inside ? at.barycentric : locator.barycentric(at.tet, P.row(p).transpose());
    e.barycentric.row(p) = w.transpose();
  });
  return e;
}

void TetEmbedding::apply(const MatrixX3d& deformedV, MatrixX3d& carried) const {
  const Eigen::Index n = deformedV.rows();
  carried.resize(corners.rows(), 3);
  // Corners are checked as they are read, which saves a separate pass over them every frame.
  std::atomic<bool> beyond{false};
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, carried.rows(), 4096),
                    [&](const tbb::blocked_range<Eigen::Index>& r) {
                      for (Eigen::Index p = r.begin(); p < r.end(); ++p) {
                        const Eigen::Array4i c = corners.row(p).transpose();
                        if ((c < 0).any() || (c >= n).any()) {
                          beyond = true;
                          continue;
                        }
                        Eigen::RowVector3d x = Eigen::RowVector3d::Zero();
                        for (int j = 0; j < 4; ++j) x += barycentric(p, j) * deformedV.row(c[j]);
                        carried.row(p) = x;
                      }
                    });
  if (beyond)
    throw UsageError("tet embedding: a tet corner is beyond the " + std::to_string(n) + " deformed vertices");
}

MatrixX3d TetEmbedding::apply(const MatrixX3d& deformedV) const {
  MatrixX3d carried;
  apply(deformedV, carried);
  return carried;
}

}  // namespace vesalius
