// Inside or outside of a closed surface from the closest point, by the angle-weighted pseudonormal
// (internal to meshing).
//
// Bærentzen and Aanæs, "Signed distance computation using the angle weighted pseudonormal", IEEE TVCG
// 11(3), 2005: for a closed, consistently oriented 2-manifold, p lies outside exactly when (p - q) · n > 0,
// q the closest point of the surface to p and n the pseudonormal of the feature q lies on: the face
// normal inside a face, the sum of the two face normals on an edge, the angle-weighted sum of the face
// normals at a vertex. Exact up to round-off, unlike OpenVDB's sign heuristics for voxels that
// touch the surface.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/triangle_tree.h"

#include <cstdint>
#include <unordered_map>

namespace vesalius::meshing::detail {

class PseudonormalSign {
 public:
  // Checks that every directed edge of F (#F by 3) occurs once and its reverse once (a closed,
  // consistently oriented 2-manifold) and that all pieces of the surface face the same way (all enclose
  // positive volumes, or all negative: inward-facing surfaces work too); usable() is false otherwise.
  explicit PseudonormalSign(const TriMesh& mesh);
  bool usable() const { return usable_; }
  // True if p lies strictly inside; `closest` is the closest point of the mesh to p (TriangleTree).
  bool inside(const Eigen::Vector3d& p, const ClosestPoint& closest) const;

 private:
  static std::uint64_t edgeKey(int a, int b);  // unordered
  const MatrixX3i& F_;
  MatrixX3d faceNormals_, vertexNormals_;
  std::unordered_map<std::uint64_t, Eigen::Vector3d> edgeNormals_;
  bool usable_ = false;
};

}  // namespace vesalius::meshing::detail
