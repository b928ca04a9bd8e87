// Test patients with a ground truth we control: a CT and its label map warped by a smooth, invertible
// non-rigid field that changes chosen organs' sizes and positions (issue 30: "the shipped CT and its labels
// warped by a smooth non-rigid field with organ sizes changed by ±15 % and shifts of 10–20 mm"). A fit
// scored on the warped labels is not scored on the scan its template came from.
//
// The field is the time-1 flow of a stationary velocity field, so it is a diffeomorphism by construction
// (its Jacobian is exp of the integrated divergence, never zero); the Jacobian is measured on the grid all
// the same. Organ o (centroid c, voxels at RMS radius ρ and greatest radius ρmax from c) contributes
//     v_o(x) = w_o(|x - c|) · (A (x - c) + b),   A = diag(log s),   b_a = t_a · log s_a / (s_a - 1),
// w_o = 1 within ρ, falling to 0 at ρmax + ρ by the C2 smoothstep 1 - (10u³ - 15u⁴ + 6u⁵). Where w_o = 1
// the flow is exactly x ↦ c + diag(s)(x - c) + t: the organ's core is scaled by s about its centroid and
// shifted by t; its rim, where w_o falls, less, so the organ is bent as well as scaled, and the tissue
// around follows smoothly. Where the organs' weights sum past 1 their velocities are averaged with those
// weights (else added), so that neighbouring organs' scales do not compound. Images are resampled by
// backward mapping (each output voxel centre traced back along the flow by RK4): labels nearest-neighbour
// (background where the point left the scan), HU trilinear (edge values extend beyond the scan).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vesalius::test {

struct OrganWarp {
  std::string organ;        // label name in the map's table
  Eigen::Vector3d scale;    // about the organ's centroid, per LPS axis (0.85 … 1.15 for the issue's ±15 %)
  Eigen::Vector3d shiftMm;  // of the organ's core, LPS mm
};

// The flow of the organs' velocity fields, set up on a label map.
class WarpField {
 public:
  WarpField(const LabelMap& labels, const std::vector<OrganWarp>& warps, int steps = 16);
  Eigen::Vector3d forward(const Eigen::Vector3d& x) const;   // φ(x), mm
  Eigen::Vector3d backward(const Eigen::Vector3d& y) const;  // φ⁻¹(y), mm

 private:
  struct Part {
    Eigen::Vector3d centre, a, b;
    double plateau, support;  // mm
  };
  Eigen::Vector3d velocity(const Eigen::Vector3d& x) const;
  Eigen::Vector3d flow(Eigen::Vector3d x, double sign) const;
  bool atRest(const Eigen::Vector3d& x) const;
  std::vector<Part> parts_;
  int steps_;
};

struct WarpedPatient {
  Image ct;         // the CT resampled through φ⁻¹ (trilinear)
  LabelMap labels;  // the labels resampled through φ⁻¹ (nearest): the ground truth
  // det ∂φ/∂x over the grid, from central differences of φ⁻¹ at the voxel centres.
  double minJacobian = 0, maxJacobian = 0;
};

// ct and labels on the same grid. Throws std::runtime_error if an organ is not in the table or has no voxels.
WarpedPatient warpPatient(const Image& ct, const LabelMap& labels, const std::vector<OrganWarp>& warps);

}  // namespace vesalius::test
