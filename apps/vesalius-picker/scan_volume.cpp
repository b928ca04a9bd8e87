#include "scan_volume.h"

#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkPointData.h>
#include <vtkUnsignedShortArray.h>

#include <Eigen/LU>

#include <cmath>
#include <cstring>

namespace vesalius::picker {
namespace {

template <class VtkArray, class T>
vtkSmartPointer<vtkImageData> copyToIndexSpace(const GridGeometry& geometry, const std::vector<T>& values) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(geometry.size.x(), geometry.size.y(), geometry.size.z());
  image->SetOrigin(0, 0, 0);
  image->SetSpacing(1, 1, 1);
  auto array = vtkSmartPointer<VtkArray>::New();
  array->SetNumberOfTuples(vtkIdType(values.size()));
  std::memcpy(array->GetPointer(0), values.data(), values.size() * sizeof(T));
  image->GetPointData()->SetScalars(array);
  return image;
}

}  // namespace

vtkSmartPointer<vtkMatrix4x4> toVtkMatrix(const Eigen::Matrix4d& matrix) {
  auto result = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) result->SetElement(r, c, matrix(r, c));
  return result;
}

ScanVolume::ScanVolume(Image scan)
    : scan_(std::move(scan)),
      voxels_(copyToIndexSpace<vtkFloatArray>(scan_.geometry, scan_.values)),
      worldToIndex_(toVtkMatrix(scan_.geometry.indexToWorldMatrix().inverse())) {}

std::optional<Eigen::Vector3i> ScanVolume::voxelAt(const Eigen::Vector3d& world) const {
  const Eigen::Vector3d index = geometry().worldToIndex(world);
  const Eigen::Vector3i voxel(int(std::lround(index.x())), int(std::lround(index.y())),
                              int(std::lround(index.z())));
  if (!geometry().contains(voxel.x(), voxel.y(), voxel.z())) return std::nullopt;
  return voxel;
}

vtkSmartPointer<vtkImageData> indexSpaceLabels(const Grid<std::uint16_t>& labels) {
  return copyToIndexSpace<vtkUnsignedShortArray>(labels.geometry, labels.values);
}

}  // namespace vesalius::picker
