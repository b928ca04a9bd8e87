// Per-tet affine maps (tet_affine_maps.h).
#include "vesalius/posing/tet_affine_maps.h"

#include "vesalius/core/error.h"

#include <tbb/parallel_for.h>

#include <Eigen/LU>

#include <string>

namespace vesalius::posing {
namespace {

Eigen::Matrix3d edges(const MatrixX3d& V, const MatrixX4i& T, Eigen::Index t) {
  Eigen::Matrix3d E;
  for (int k = 0; k < 3; ++k) E.col(k) = (V.row(T(t, k + 1)) - V.row(T(t, 0))).transpose();
  return E;
}

}  // namespace

std::vector<Eigen::Affine3d> tetAffineMaps(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV) {
  if (restV.rows() != posedV.rows())
    throw UsageError("tet affine maps: " + std::to_string(restV.rows()) + " rest and " +
                     std::to_string(posedV.rows()) + " posed vertices");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= restV.rows()))
    throw BadInput("", "tet affine maps: a tet refers to a vertex that does not exist");
  std::vector<Eigen::Affine3d> maps(std::size_t(T.rows()));
  tbb::parallel_for(Eigen::Index(0), T.rows(), [&](Eigen::Index t) {
    Eigen::Matrix3d inverse;
    bool invertible = false;
    edges(restV, T, t).computeInverseWithCheck(inverse, invertible, 0.0);
    if (!invertible) throw BadInput("", "tet affine maps: rest tet " + std::to_string(t) + " is flat");
    Eigen::Affine3d& A = maps[std::size_t(t)];
    A.linear() = edges(posedV, T, t) * inverse;
    A.translation() = posedV.row(T(t, 0)).transpose() - A.linear() * restV.row(T(t, 0)).transpose();
  });
  return maps;
}

}  // namespace vesalius::posing
