// ICP markers (Wang et al. 2021, eq. 5, second sum): scan points that must lie on the deformed tet mesh's
// surface. Each Gauss-Newton iteration takes the closest surface point of every marker, fixed as a
// barycentric combination of its triangle's vertices (as a point of the triangle's tet), as that
// iteration's A_k (Appendix F).
#pragma once

#include "vesalius/fit/point_constraints.h"

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::fit {

class SurfaceProjection {
 public:
  // T: #T by 4 tets; the surface is their boundary (tetBoundary).
  explicit SurfaceProjection(const MatrixX4i& T);

  // For positions x (3#V stacked) and markers (#M by 3): the closest surface points as constraints of
  // weight c pulling them onto the markers.
  std::vector<PointConstraint> closestPoints(const Eigen::VectorXd& x, const MatrixX3d& markers, double c) const;
  // Distance (mm) of every marker to the surface at x: #M.
  Eigen::VectorXd distances(const Eigen::VectorXd& x, const MatrixX3d& markers) const;

  const MatrixX3i& faces() const { return F_; }

 private:
  MatrixX4i T_;
  MatrixX3i F_;
  std::vector<int> faceTet_;  // #F: the tet each boundary triangle belongs to
};

}  // namespace vesalius::fit
