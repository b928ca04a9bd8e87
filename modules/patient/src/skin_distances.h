// The signed distances to a closed skin that transfer/bones_inside_skin.h and bones_warped_into_skin.h
// take (transfer::SkinDistanceFunction), shared by the full-body reference (its bones moved inside its
// skin), and an anatomy's tissues bent inside its skin by one displacement, shared by the reference's
// organs (reference_organs.h) and the reference completed into a patient (reference_completion.h).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/transfer/anatomy_checks.h"
#include "vesalius/transfer/bones_inside_skin.h"
#include "vesalius/transfer/bones_warped_into_skin.h"

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

// Every tissue of `anatomy` (and its points) moved by one smooth displacement that brings the vertices
// outside its skin inside (transfer::warpIntoSkin), so that tissues side by side stay so; unmoved when none
// is outside. Returns the displacement.
inline transfer::InsideSkinWarp bendTissuesIntoSkin(ReferenceAnatomy& anatomy,
                                                    const transfer::InsideSkinWarpOptions& options) {
  MatrixX3d all(0, 3);
  for (const ReferenceTissue& t : anatomy.tissues) {
    all.conservativeResize(all.rows() + t.mesh.V.rows(), 3);
    all.bottomRows(t.mesh.V.rows()) = t.mesh.V;
  }
  if (all.rows() == 0) return {};
  transfer::InsideSkinWarp bend = transfer::warpIntoSkin(all, skinDistances(anatomy.skin), options);
  if (bend.outsideBefore == 0) return bend;
  for (ReferenceTissue& t : anatomy.tissues) t.mesh.V = bend.apply(t.mesh.V);
  for (ReferencePoint& p : anatomy.points) p.position = bend.apply(p.position.transpose()).transpose();
  return bend;
}

}  // namespace vesalius::patient
