// A scan handed to VTK: the voxels in index space (origin 0, spacing 1) and the world <-> index maps.
//
// VTK's image pipeline is given plain voxel indices; every slice view reslices them through
// worldToIndex, so the direction matrix (oblique scans) is honoured exactly as ITK defines it.
#pragma once

#include "vesalius/core/grid.h"

#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <optional>


namespace vesalius::picker {

class ScanVolume {
 public:
  explicit ScanVolume(Image scan);

  const Image& image() const { return scan_; }
  const GridGeometry& geometry() const { return scan_.geometry; }
  vtkImageData* indexSpaceImage() const { return voxels_; }
  // 4x4 homogeneous map from LPS world millimetres to continuous voxel index.
  vtkMatrix4x4* worldToIndex() const { return worldToIndex_; }

  // The voxel nearest to a world point, if inside the grid.
  std::optional<Eigen::Vector3i> voxelAt(const Eigen::Vector3d& world) const;
  float valueAt(const Eigen::Vector3i& voxel) const { return scan_.at(voxel.x(), voxel.y(), voxel.z()); }

 private:
  Image scan_;
  vtkSmartPointer<vtkImageData> voxels_;
  vtkSmartPointer<vtkMatrix4x4> worldToIndex_;
};

// The same for a label map: index-space voxels, as unsigned short.
vtkSmartPointer<vtkImageData> indexSpaceLabels(const Grid<std::uint16_t>& labels);

// Eigen 4x4 to VTK.
vtkSmartPointer<vtkMatrix4x4> toVtkMatrix(const Eigen::Matrix4d& matrix);

}  // namespace vesalius::picker
