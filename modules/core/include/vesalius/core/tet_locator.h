// Point location in a tetrahedral mesh: which tet holds a point, and its barycentric coordinates.
//
// Build once, query many times (thread-safe). Used to embed surfaces, markers and tissue vertices in
// tet meshes (Sujar et al. 2018, §3.4; Wang et al. 2021, §4.3). Sujar et al.'s §3.4 finds each vertex's tet through a spatial hash;
// here a bounding-volume hierarchy does it, and a batch of points is visited in Morton (Z-curve) order, so
// that consecutive queries walk the same tree nodes and tets while they are still in cache. The order
// changes only the speed: each point's answer is the one a single query gives.
#pragma once

#include "vesalius/core/box_tree.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <optional>
#include <vector>

namespace vesalius {

struct TetLocation {
  int tet = -1;
  Eigen::Vector4d barycentric = Eigen::Vector4d::Zero();  // weights of T(tet, 0..3), summing to 1
  bool inside = false;  // tet contains the point (else it is the nearest tet)
};

class TetLocator {
 public:
  // V: #V by 3, T: #T by 4. The locator keeps copies of both.
  TetLocator(const MatrixX3d& V, const MatrixX4i& T);

  // The tet containing p (within `tolerance` in barycentric terms), or nothing if p is outside.
  std::optional<TetLocation> locate(const Eigen::Vector3d& p, double tolerance = 1e-9) const;
  // The containing tet if there is one, else the tet whose clamped barycentric point is nearest to p;
  // barycentric weights are then those of the nearest point (all in [0, 1]).
  TetLocation locateOrNearest(const Eigen::Vector3d& p) const;
  // P: #P by 3. One locateOrNearest(p) per row of P (the same answers), in parallel, in Morton order.
  std::vector<TetLocation> locateOrNearest(const MatrixX3d& P) const;

  // Barycentric coordinates of p with respect to tet t (may be outside [0, 1]).
  Eigen::Vector4d barycentric(int t, const Eigen::Vector3d& p) const;

 private:
  MatrixX3d V_;
  MatrixX4i T_;
  BoxTree tree_;
};

}  // namespace vesalius
