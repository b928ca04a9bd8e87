// The three slice orientations of the picker and how a slice plane maps to LPS world space. No VTK.
//
// Views show world-aligned planes, whatever the scan's direction matrix: an oblique scan is resampled
// onto them, so a point picked on screen is always a plain LPS point. Display conventions are those of
// 3D Slicer (radiological): axial seen from the feet with the patient's left on the screen's right and
// anterior up; coronal seen from the front, left on the right, superior up; sagittal seen from the
// patient's left, anterior on the left, superior up.
#pragma once

#include "vesalius/core/grid.h"

#include <Eigen/Core>

#include <array>

namespace vesalius::picker {

enum class SliceAxis { Axial, Coronal, Sagittal };
inline constexpr std::array<SliceAxis, 3> kSliceAxes = {SliceAxis::Axial, SliceAxis::Coronal,
                                                        SliceAxis::Sagittal};
const char* sliceAxisName(SliceAxis axis);  // "axial", "coronal", "sagittal"

// A plane's own coordinates (x right on screen, y up, z = depth along `normal`) and the world.
// world = right * x + up * y + normal * z.
struct SliceFrame {
  Eigen::Vector3d right, up, normal;  // orthonormal, normal = right x up
  // Where "next slice" goes, as in 3D Slicer: superior (axial), anterior (coronal), right (sagittal);
  // normal or -normal.
  Eigen::Vector3d forward;

  static SliceFrame of(SliceAxis axis);
  Eigen::Matrix3d planeToWorld() const;  // columns right, up, normal
  Eigen::Vector3d toPlane(const Eigen::Vector3d& world) const { return planeToWorld().transpose() * world; }
  Eigen::Vector3d toWorld(const Eigen::Vector3d& plane) const { return planeToWorld() * plane; }
};

// Where a scan lies in one plane's coordinates.
struct SliceExtent {
  Eigen::Vector3d centre;               // the grid's centre voxel position, plane coordinates
  Eigen::Vector3d halfSize;             // half the extent of the voxel centres along x, y, z
  double depthStep = 1;                 // one slice step, mm: at most one voxel along any index axis
};
SliceExtent sliceExtent(const GridGeometry& grid, const SliceFrame& frame);

}  // namespace vesalius::picker
