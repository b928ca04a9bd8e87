// The body frame and the head of a standing human skin ("Anatomically correct skeleton
// alignment", GRAPP 2012, §3.1).
//
// - Transverse plane: its normal is the mean of the two legs' ankle→hip vectors (rough joints given).
// - Head: the skin is cut by planes parallel to the transverse plane, from its topmost point down, every
//   `sliceSpacing` mm. Each cut is PCA'd; its diameter is its extent along the major axis. Slicing stops
//   at the first slice whose diameter fell below `shrinkRatio` times the largest diameter so far
//   (chin→throat), or whose major axis turned by `axisSwitchDegrees` or more from that largest slice's
//   (head→torso: the head is longer front to back, the trunk side to side). The slices above are the head.
// - Sagittal and frontal planes: principal axes of all head-slice points projected into one transverse
//   plane; the major axis is the frontal normal (the head is longer forward than sideways).
// - Head centroid: the perimeter-weighted mean of the slices' centroids.
// - Head-spine joint: the centroid projected onto the plane of the slice reaching furthest forward (the
//   nose), then moved front-back inside that plane.
//
// Deviations, plainly:
// - Signs: PCA leaves them open; the sagittal normal is made to point to the left hip and ankle, the
//   frontal normal is transverse × sagittal (posterior, so that the frame is right-handed, LPS-like).
// - The paper's text breaks off before it says how the joint is moved inside the transverse plane ("by
//   looking at a real skull cut along the transverse plane ... the back ..."). Here the joint is put at
//   `jointDepthFraction` of the nose slice's back-to-front extent, from the back, keeping its left-right
//   position: 0.35 because in Rajagopal 2016's skull and spine meshes (testdata/skeleton-opensim) the
//   atlas's upper facets lie 35% of the skull's back-to-front length from its back.
// - The axis switch counts only for a clearly elongated slice (sqrt(λ1/λ2) ≥ `minElongation`, the ratio
//   of its principal standard deviations): head slices are nearly round (1.0-1.3 on MakeHuman, where the
//   ears turn the axis sideways for a few slices), the trunk with its shoulders is not.
// - A cut keeps every polygon of the plane, not only the head's: the arms must hang below the chin.
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::transfer {

struct BodyFrameOptions {
  double sliceSpacing = 4.0;         // mm between consecutive transverse cuts
  double shrinkRatio = 0.75;         // chin→throat: diameter < shrinkRatio · the largest diameter
  double axisSwitchDegrees = 60.0;   // head→torso: major axis turned this far from the largest slice's
  double minElongation = 1.4;        // the axis switch counts only for slices this elongated
  double jointDepthFraction = 0.35;  // head-spine joint: this far from the back of the nose slice
};

// Rough joints of the legs (any consistent skeleton: MakeHuman's, a fitted one), mm.
struct LegJoints {
  Eigen::Vector3d leftHip, leftAnkle, rightHip, rightAnkle;
};

struct BodyFrame {
  Eigen::Vector3d sagittalNormal;    // unit, towards the body's left
  Eigen::Vector3d frontalNormal;     // unit, towards its back
  Eigen::Vector3d transverseNormal;  // unit, upwards
  Eigen::Vector3d sagittalPoint;     // a point on the sagittal plane: the head centroid
  int headSlices = 0;                // cuts above the stop
  double stopLevel = 0;              // transverseNormal · x of the cut that stopped the head
  bool stoppedByShrink = false;      // which criterion stopped it (else the axis switch)
  Eigen::Vector3d headCentroid;
  Eigen::Vector3d headSpineJoint;

  // Columns: sagittal, frontal, transverse normal. A rotation; the identity for an LPS-aligned body.
  Eigen::Matrix3d axes() const;
};

// V: #V by 3 skin vertices (mm), F: #F by 3 triangles (a closed skin; holes at eyes or mouth are fine).
// Throws BadInput when the legs give no up direction or the skin has no head (no cut stops slicing
// before the bottom of the mesh); UsageError for options out of range.
BodyFrame computeBodyFrame(const MatrixX3d& V, const MatrixX3i& F, const LegJoints& legs,
                           const BodyFrameOptions& options = {});

}  // namespace vesalius::transfer
