#include "vesalius/posing/principal_axis.h"

#include "vesalius/core/error.h"
#include "vesalius/core/principal_axes.h"

namespace vesalius::posing {

Eigen::Vector3d principalAxis(const MatrixX3d& P, const Eigen::Vector3d& towards) {
  if (P.rows() < 2) throw BadInput("", "a principal axis needs at least two points");
  const PrincipalAxes a = principalAxes(P);
  if (!(a.variances[0] > 0)) throw BadInput("", "a principal axis needs two distinct points");
  if (a.variances[0] - a.variances[1] <= 1e-9 * a.variances[0])
    throw BadInput("", "the points have no single longest axis");
  const Eigen::Vector3d axis = a.axes.col(0);
  return axis.dot(towards) < 0 ? Eigen::Vector3d(-axis) : axis;
}

}  // namespace vesalius::posing
