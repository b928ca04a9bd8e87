// Reading and writing surface (TriMesh) and tetrahedral (TetMesh) mesh files, chosen by extension,
// and the summary `vesalius info` prints for a mesh.
//
//   surfaces  .stl (ASCII or binary)  .obj  .ply  .vtk (legacy polydata)  .vtp  .glb (binary glTF, gltf.h)
//   tets      .vtu  .vtk (legacy unstructured grid)  .node/.ele (TetGen, with .face)  .mesh (MEDIT)  .msh (Gmsh)
//
// Readers return LPS millimetres, validated (TriMesh/TetMesh::validate), tets positively oriented; any
// problem is a one-line BadInput naming the file. Writers go through writeAtomically: no partial output,
// an existing output kept unless options.force (UsageError otherwise).
//
// The text formats are described in mesh_formats.h. The VTK-based ones:
//   PLY         vtkPLYReader/Writer: float32 coordinates, per-vertex uv only (u, v properties); other
//               attributes are not written. Coordinate tag in a header comment "SPACE=LPS".
//   VTK legacy  file version 4.2 (readable by VTK 8 and older tools); tag "SPACE=LPS" in the title line.
//   VTP, VTU    coordinate tag as 3D Slicer writes it: field data string array "SPACE" = "LPS".
// In these, point data and cell data arrays are attributes: integer arrays with one component become
// integer attributes, everything else real (#elements by components). uv is the active TCoords point
// array when each vertex has one uv; a mesh with uv seams (a vertex with several uv) is written with a
// #F by 6 cell array "corner_uv" (u0 v0 u1 v1 u2 v2) instead, which the reader turns back into UV/FUV.
// Polygons are fan-triangulated; triangle strips and, in tet meshes, any cell that is not a tetrahedron
// are rejected. VTU/VTK tet meshes carry V, T and their attributes; F is not written (tetBoundary gives it).
// .glb holds V and F only: written as one grey node named after the file, read as all its nodes in one mesh.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/mesh.h"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace vesalius::io {

struct MeshWriteOptions : WriteOptions {
  // STL, PLY, VTK legacy, VTP, VTU: binary (compact, exact for VTK's Float64) or ASCII text.
  bool binary = true;
};

enum class MeshKind { kSurface, kTetrahedral };

// What a mesh file holds, from its extension (and for .vtk its header); nullopt when the extension is
// not a mesh format. Throws BadInput if a .vtk file cannot be read or holds neither polydata nor an
// unstructured grid.
std::optional<MeshKind> meshFileKind(const std::string& path);

TriMesh readTriMesh(const std::string& path);
TetMesh readTetMesh(const std::string& path);

// For TetGen, `path` ends in .node or .ele and names all three files (.face only when F is not empty).
void writeTriMesh(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options = {});
void writeTetMesh(const std::string& path, const TetMesh& mesh, const MeshWriteOptions& options = {});

struct TriMeshSummary {
  Eigen::Index vertices = 0, triangles = 0;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();  // bounds, mm (zero if empty)
  long boundaryEdges = 0;     // edges of one triangle
  long nonManifoldEdges = 0;  // edges of three or more triangles
  int components = 0;         // sets of triangles connected through shared vertices
  bool closed = false;        // a closed 2-manifold: no boundary and no non-manifold edges
  long selfIntersections = 0;  // pairs of triangles that cross (core/self_intersections.h)
  std::optional<double> volume;  // mm^3 by the divergence theorem, only when closed (negative if inside out)
  bool hasUv = false;
  std::vector<std::string> vertexAttributes, faceAttributes;  // names
};

struct TetMeshSummary {
  Eigen::Index vertices = 0, tets = 0, triangles = 0;
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();
  double totalVolume = 0, minVolume = 0, maxVolume = 0;  // signed tet volumes, mm^3 (zero if no tets)
  long inverted = 0;                  // tets with negative volume
  std::map<int, long> tetsPerLabel;   // integer tet attribute kLabel; empty without one
  std::map<int, double> volumePerLabel;  // mm^3, same keys
  std::vector<std::string> vertexAttributes, tetAttributes, faceAttributes;  // names
};

TriMeshSummary summarize(const TriMesh& mesh);
TetMeshSummary summarize(const TetMesh& mesh);

// The summaries as a few lines of text for `vesalius info`.
std::string describe(const TriMeshSummary& summary);
std::string describe(const TetMeshSummary& summary);

// The VTK-based formats by path (used by the functions above; see the table at the top).
TriMesh readVtkSurface(const std::string& path);  // .ply, .vtk, .vtp
TetMesh readVtkTetMesh(const std::string& path);  // .vtu, .vtk
void writeVtkSurface(const TriMesh& mesh, const std::string& path, bool binary);
void writeVtkTetMesh(const TetMesh& mesh, const std::string& path, bool binary);

}  // namespace vesalius::io
