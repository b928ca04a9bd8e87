// The signed distances to a closed skin that transfer/bones_inside_skin.h and bones_warped_into_skin.h
// take (transfer::SkinDistanceFunction), shared by the full-body reference (its bones moved inside its
// skin) and the reference's organs (reference_organs.h: what the transfer left outside bent inside).
#pragma once

#include "vesalius/core/triangle_tree.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/transfer/anatomy_checks.h"
#include "vesalius/transfer/bones_inside_skin.h"

#include <memory>

namespace vesalius::patient {

// Signed distances to a closed skin (transfer::SkinDistanceFunction): distance and outward direction from
// the closest point on it, the side from the signed distance field the transfer's rules R5, R6 use
// (meshing/body_distance.h).
inline transfer::SkinDistanceFunction skinDistances(const TriMesh& skin) {
  const auto field = std::make_shared<const Grid<float>>(meshing::bodySignedDistance(skin).signedDistance);
  const auto tree = std::make_shared<const TriangleTree>(skin.V, skin.F);
  return [field, tree](const MatrixX3d& P) {
    const std::vector<ClosestPoint> closest = tree->closest(P);
    const Eigen::VectorXd sampled = transfer::sampleSignedDistance(*field, P, meshing::kDistanceBandMm);
    transfer::SkinDistances d{Eigen::VectorXd(P.rows()), MatrixX3d::Zero(P.rows(), 3)};
    for (Eigen::Index r = 0; r < P.rows(); ++r) {
      const double side = sampled[r] < 0 ? -1.0 : 1.0;
      const Eigen::Vector3d away = P.row(r).transpose() - closest[std::size_t(r)].point;
      d.distance[r] = side * away.norm();
      if (away.norm() > 1e-9) d.outward.row(r) = side * away.normalized().transpose();
    }
    return d;
  };
}

}  // namespace vesalius::patient
