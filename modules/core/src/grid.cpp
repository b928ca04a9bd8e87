#include "vesalius/core/grid.h"

#include "vesalius/core/error.h"

#include <Eigen/LU>

#include <cmath>

namespace vesalius {

Eigen::Vector3d GridGeometry::indexToWorld(const Eigen::Vector3d& index) const {
  return origin + direction * spacing.cwiseProduct(index);
}

Eigen::Vector3d GridGeometry::worldToIndex(const Eigen::Vector3d& world) const {
  return (direction.inverse() * (world - origin)).cwiseQuotient(spacing);
}

bool GridGeometry::seesPoint(const Eigen::Vector3d& world) const {
  const double tolerance = 1e-9;
  const Eigen::Array3d index = worldToIndex(world).array();
  return (index >= -tolerance).all() && (index <= size.cast<double>().array() - 1.0 + tolerance).all();
}

Eigen::Matrix4d GridGeometry::indexToWorldMatrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = direction * spacing.asDiagonal();
  m.topRightCorner<3, 1>() = origin;
  return m;
}

std::string GridGeometry::orientationCode() const {
  // LPS world axes: +x points Left, +y Posterior, +z Superior.
  static constexpr char kPositive[3] = {'L', 'P', 'S'};
  static constexpr char kNegative[3] = {'R', 'A', 'I'};
  std::string code;
  for (int axis = 0; axis < 3; ++axis) {
    Eigen::Index dominant = 0;
    direction.col(axis).cwiseAbs().maxCoeff(&dominant);
    code += direction(dominant, axis) > 0 ? kPositive[dominant] : kNegative[dominant];
  }
  return code;
}

void GridGeometry::validate(const std::string& source) const {
  if ((size.array() <= 0).any())
    throw BadInput(source, "image size " + std::to_string(size.x()) + "x" + std::to_string(size.y()) + "x" +
                               std::to_string(size.z()) + " is empty");
  for (int a = 0; a < 3; ++a)
    if (!(std::isfinite(spacing(a)) && spacing(a) > 0))
      throw BadInput(source, "voxel spacing along axis " + std::to_string(a) + " is " +
                                 std::to_string(spacing(a)) + " (must be positive)");
  if (!origin.allFinite()) throw BadInput(source, "image origin is not finite");
  if (!direction.allFinite() || std::abs(direction.determinant()) < 1e-6)
    throw BadInput(source, "image direction matrix is singular");
}

const char* pixelTypeName(PixelType t) {
  switch (t) {
    case PixelType::UInt8: return "uint8";
    case PixelType::Int8: return "int8";
    case PixelType::UInt16: return "uint16";
    case PixelType::Int16: return "int16";
    case PixelType::UInt32: return "uint32";
    case PixelType::Int32: return "int32";
    case PixelType::Float32: return "float32";
    case PixelType::Float64: return "float64";
  }
  return "unknown";
}

}  // namespace vesalius
