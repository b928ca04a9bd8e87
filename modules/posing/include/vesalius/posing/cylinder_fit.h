// Least-squares cylinder through points: the axis of a hinge joint (Sujar et al. 2018, §3.1, estimates a bone's
// rotation centre and axes "from a set of annotated vertices"; for the knee, the femoral condyles facing
// the tibia, whose posterior and distal arcs lie close to one cylinder about the flexion axis, and for the
// ankle the talar trochlea facing the tibia; skeleton_from_bone_meshes.h).
//
// The geometric residuals dist(p, axis) − r are minimised by Levenberg–Marquardt over the axis direction
// (two angles), its position across the axis (two offsets) and r. It starts from `axisGuess` through the
// points' mean with the algebraic circle fit (Kåsa) of the points projected along the guess, so the guess
// need only be on the right side of the valley: a cap of a cylinder is ill-determined along its axis
// otherwise. Points on a cylinder give it back exactly (to rounding).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::posing {

struct CylinderFitOptions {
  int maxIterations = 100;   // Levenberg–Marquardt steps after the circle fit
  double tolerance = 1e-12;  // stop when a step moves the axis less than this times the radius
};

struct CylinderFit {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the axis, nearest the points' mean
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // unit, on the side of axisGuess
  double radius = 0;
  double rmsResidual = 0;  // root mean square of dist(p, axis) − radius
};

// P: #P by 3 points (#P >= 5, not all on one line or circle's plane). axisGuess: a nonzero direction.
// Throws BadInput if the points do not determine a cylinder (fewer than 5, or a degenerate circle fit).
CylinderFit fitCylinder(const MatrixX3d& P, const Eigen::Vector3d& axisGuess, const CylinderFitOptions& options = {});

}  // namespace vesalius::posing
