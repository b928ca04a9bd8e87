// Least-squares sphere through points: the rotation centre of a ball-and-socket joint (Sujar et al. 2018, §3.1:
// "we estimate ... the bone rotation centre from a set of annotated vertices"; for the hip, the femoral
// head's points facing the acetabulum, skeleton_from_bones.h).
//
// The algebraic fit first (Kåsa: |p|² = 2 c·p + r² − |c|², linear in c and r² − |c|², solved by QR on
// points centred at their mean), then Gauss–Newton on the geometric residuals |p − c| − r, which the
// algebraic fit biases towards small spheres when the points cover only a cap. Points on a sphere give it
// back exactly (to rounding) from either step.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::posing {

struct SphereFitOptions {
  int maxIterations = 50;      // Gauss–Newton steps after the algebraic fit
  double tolerance = 1e-12;    // stop when a step moves centre and radius less than this times the radius
};

struct SphereFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  double rmsResidual = 0;  // root mean square of |p − centre| − radius
};

// P: #P by 3 points (#P >= 4, not all on one plane). Throws BadInput otherwise.
SphereFit fitSphere(const MatrixX3d& P, const SphereFitOptions& options = {});

}  // namespace vesalius::posing
