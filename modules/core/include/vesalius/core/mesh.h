// Triangle and tetrahedral meshes: plain Eigen matrices plus named attributes (DESIGN.md, "Geometry types").
//
// Coordinates are millimetres in LPS world space once inside Vesalius; readers and writers in `io` do the
// conversions. Faces and tets index rows of V (0-based).
#pragma once

#include "vesalius/core/attributes.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <string>

namespace vesalius {

using MatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3>;
using MatrixX2d = Eigen::Matrix<double, Eigen::Dynamic, 2>;
using MatrixX3i = Eigen::Matrix<int, Eigen::Dynamic, 3>;
using MatrixX4i = Eigen::Matrix<int, Eigen::Dynamic, 4>;

struct TriMesh {
  MatrixX3d V;  // #V by 3 vertex positions
  MatrixX3i F;  // #F by 3 triangles, counter-clockwise seen from outside
  // Texture coordinates as in OBJ: #UV by 2 coordinates and #F by 3 indices into UV (empty if none).
  MatrixX2d UV;
  MatrixX3i FUV;
  AttributeSet vertexAttributes;  // rows: #V
  AttributeSet faceAttributes;    // rows: #F

  // Throws BadInput naming `source` on non-finite coordinates, out-of-range indices or mismatched
  // attribute sizes. Readers call it so nothing downstream sees a broken mesh.
  void validate(const std::string& source) const;
};

struct TetMesh {
  MatrixX3d V;  // #V by 3 vertex positions
  MatrixX4i T;  // #T by 4 tetrahedra, positively oriented: (v1-v0)·((v2-v0)×(v3-v0)) > 0
  MatrixX3i F;  // #F by 3 boundary triangles when the file carries them (may be empty)
  AttributeSet vertexAttributes;  // rows: #V
  AttributeSet tetAttributes;     // rows: #T
  AttributeSet faceAttributes;    // rows: #F

  void validate(const std::string& source) const;
};

// Both meshes as one (b's indices shifted past a's vertices); uv and attributes are dropped.
TriMesh concatenate(const TriMesh& a, const TriMesh& b);

// Signed volume of each tet (#T): positive for the orientation above.
Eigen::VectorXd tetVolumes(const MatrixX3d& V, const MatrixX4i& T);

// Boundary triangles of a tet mesh (faces used by exactly one tet), oriented outward.
MatrixX3i tetBoundary(const MatrixX4i& T);

// The boundary of a tet mesh as a surface of its own: V: #V by 3, T: #T by 4; only the vertices its
// triangles use (renumbered).
TriMesh tetBoundarySurface(const MatrixX3d& V, const MatrixX4i& T);

}  // namespace vesalius
