// Dense 3-D grids with their place in the world (DESIGN.md, "Units and space").
//
// A voxel index (i, j, k) maps to the LPS world point  origin + direction · diag(spacing) · (i, j, k),
// exactly as ITK's physical space. Values are stored with i fastest, then j, then k.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace vesalius {

struct GridGeometry {
  Eigen::Vector3i size = Eigen::Vector3i::Zero();     // voxels along i, j, k
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // world position of voxel (0,0,0), mm, LPS
  Eigen::Vector3d spacing = Eigen::Vector3d::Ones();  // mm
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();  // columns: world directions of i, j, k

  std::int64_t voxelCount() const { return std::int64_t(size.x()) * size.y() * size.z(); }
  std::int64_t linearIndex(int i, int j, int k) const {
    return i + std::int64_t(size.x()) * (j + std::int64_t(size.y()) * k);
  }
  bool contains(int i, int j, int k) const {
    return i >= 0 && j >= 0 && k >= 0 && i < size.x() && j < size.y() && k < size.z();
  }
  // index · spacing · direction + origin, for integer or continuous indices.
  Eigen::Vector3d indexToWorld(const Eigen::Vector3d& index) const;
  Eigen::Vector3d worldToIndex(const Eigen::Vector3d& world) const;
  // Whether a world point lies within the box of the voxel centres (continuous index in [0, size - 1] along
  // each axis, to 1e-9 voxel): where the scan has seen. A label cut by the scan's edge is closed half a
  // voxel beyond it.
  bool seesPoint(const Eigen::Vector3d& world) const;
  // 4x4 homogeneous version of indexToWorld.
  Eigen::Matrix4d indexToWorldMatrix() const;

  // Three-letter orientation code of the axes as ITK and 3D Slicer print it, e.g. "LPS" or "RAS":
  // for each of i, j, k the anatomical direction it points *to*, by its dominant world component.
  std::string orientationCode() const;

  // Throws BadInput naming `source` if any spacing is not positive and finite, the direction is
  // singular, or the size is not positive.
  void validate(const std::string& source) const;
};

template <class T>
struct Grid {
  GridGeometry geometry;
  std::vector<T> values;  // geometry.voxelCount() values

  Grid() = default;
  explicit Grid(const GridGeometry& g, T fill = T()) : geometry(g), values(g.voxelCount(), fill) {}
  T& at(int i, int j, int k) { return values[geometry.linearIndex(i, j, k)]; }
  const T& at(int i, int j, int k) const { return values[geometry.linearIndex(i, j, k)]; }
};

// How a scan's values were stored on disk; writers keep it so a round trip keeps the file's type.
enum class PixelType { UInt8, Int8, UInt16, Int16, UInt32, Int32, Float32, Float64 };
const char* pixelTypeName(PixelType t);

// A scan: intensities as float (exact for every integer type up to 24 bits and for CT HU) plus the
// type they were stored as.
struct Image : Grid<float> {
  PixelType fileType = PixelType::Float32;
  using Grid<float>::Grid;
};

}  // namespace vesalius
