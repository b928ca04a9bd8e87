#include "slice_geometry.h"

#include <Eigen/Geometry>

#include <cmath>

namespace vesalius::picker {

const char* sliceAxisName(SliceAxis axis) {
  switch (axis) {
    case SliceAxis::Axial: return "axial";
    case SliceAxis::Coronal: return "coronal";
    case SliceAxis::Sagittal: return "sagittal";
  }
  return "?";
}

SliceFrame SliceFrame::of(SliceAxis axis) {
  // LPS unit vectors.
  const Eigen::Vector3d left(1, 0, 0), posterior(0, 1, 0), superior(0, 0, 1);
  SliceFrame frame;
  switch (axis) {
    case SliceAxis::Axial: frame.right = left; frame.up = -posterior; frame.forward = superior; break;
    case SliceAxis::Coronal: frame.right = left; frame.up = superior; frame.forward = -posterior; break;
    case SliceAxis::Sagittal: frame.right = posterior; frame.up = superior; frame.forward = -left; break;
  }
  frame.normal = frame.right.cross(frame.up);
  return frame;
}

Eigen::Matrix3d SliceFrame::planeToWorld() const {
  Eigen::Matrix3d m;
  m << right, up, normal;
  return m;
}

SliceExtent sliceExtent(const GridGeometry& grid, const SliceFrame& frame) {
  const Eigen::Vector3d lastIndex = (grid.size.cast<double>() - Eigen::Vector3d::Ones());
  SliceExtent extent;
  extent.centre = frame.toPlane(grid.indexToWorld(lastIndex / 2));
  // The grid is symmetric about its centre, so the half extent is the largest corner offset.
  extent.halfSize.setZero();
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d index(corner & 1 ? lastIndex.x() : 0, corner & 2 ? lastIndex.y() : 0,
                                corner & 4 ? lastIndex.z() : 0);
    const Eigen::Vector3d offset = frame.toPlane(grid.indexToWorld(index)) - extent.centre;
    extent.halfSize = extent.halfSize.cwiseMax(offset.cwiseAbs());
  }
  // Index change per mm along the normal; one step moves at most one voxel along any index axis.
  const Eigen::Vector3d indexPerMm =
      grid.spacing.cwiseInverse().asDiagonal() * (grid.direction.transpose() * frame.normal);
  extent.depthStep = 1.0 / indexPerMm.cwiseAbs().maxCoeff();
  return extent;
}

}  // namespace vesalius::picker
