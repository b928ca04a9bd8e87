// Volume restoration by a uniform normal offset (restore_volume.h).
#include "restore_volume.h"

#include "vesalius/core/mesh_measures.h"

#include <Eigen/Geometry>

#include <cmath>

namespace vesalius::meshing::detail {
namespace {

// Unit area-weighted vertex normals and the total area.
// Vertices used by no triangle keep a zero normal and do not move.
MatrixX3d vertexNormals(const MatrixX3d& V, const MatrixX3i& F, double& area) {
  MatrixX3d normals = MatrixX3d::Zero(V.rows(), 3);
  area = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::Vector3d twiceArea = (b - a).cross(c - a);
    area += 0.5 * twiceArea.norm();
    for (int k = 0; k < 3; ++k) normals.row(F(f, k)) += twiceArea.transpose();
  }
  for (Eigen::Index v = 0; v < normals.rows(); ++v)
    if (normals.row(v).norm() > 0.0) normals.row(v).normalize();
  return normals;
}

}  // namespace

bool restoreVolume(TriMesh& mesh, double targetVolume, double maxOffsetMm) {
  MatrixX3d V = mesh.V;
  for (int step = 0; step < 2; ++step) {
    double area = 0.0;
    const MatrixX3d normals = vertexNormals(V, mesh.F, area);
    if (!(area > 0.0)) return false;
    const double offset = (targetVolume - enclosedVolume(V, mesh.F)) / area;
    if (!(std::abs(offset) <= maxOffsetMm)) return false;
    V += offset * normals;
  }
  mesh.V = V;
  return true;
}

}  // namespace vesalius::meshing::detail
