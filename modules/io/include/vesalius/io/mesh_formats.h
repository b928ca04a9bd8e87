// Parsers and formatters for the mesh file formats that need neither VTK nor ITK: STL, OBJ, TetGen,
// MEDIT and Gmsh. They work on text (or bytes) in memory, not on paths, so the libFuzzer harnesses can
// call them; mesh_io.h opens files and dispatches on the extension.
//
// Every parser returns a mesh in LPS millimetres that has passed TriMesh/TetMesh::validate(source),
// with every tet positively oriented (two vertices swapped where the file had it inverted). Every error
// is a one-line BadInput naming `source` (and the line, where there is one); malformed input never
// crashes and never makes a parser allocate more than a small multiple of the input size.
//
// Coordinate tags. A writer marks its output "SPACE=LPS" where the format has a place for text; a
// reader flips x and y (RAS -> LPS) when it finds "SPACE=RAS" there, and only then:
//   STL ASCII   the "solid" line            STL binary  the 80-byte header
//   OBJ         a "#" comment line          TetGen      a "#" comment line of the .node file
//   MEDIT       a "#" comment line          Gmsh        none (files are taken as LPS)
// (PLY, VTK legacy, VTP and VTU are in mesh_io.h.)
//
// Attributes each format carries (others are not written):
//   STL      geometry only; duplicate vertices are merged on read (exact equality of coordinates).
//   OBJ      UV/FUV from vt and f v/vt[/vn]; normals (vn) are ignored. Face attribute "group"
//            (integer) when the faces belong to two or more "g" groups: a group whose name is an
//            integer gets that id (this is what the writer writes: "g <id>"); otherwise ids count
//            0, 1, ... over the groups in the order their first face appears (faces before any "g"
//            are in group "default"). Group names are not kept. Polygons are fan-triangulated.
//   TetGen   .node attributes -> vertex real "attribute" (#V by k), boundary markers -> vertex
//            integer "marker"; .ele first attribute -> tet integer kRegion, further ones -> tet
//            real "attribute"; .face triangles -> F with face integer "marker".
//   MEDIT    references -> integer kLabel of vertices, tets and triangles (Triangles -> F).
//   Gmsh     v1 ($NOD/$ELM), v2 ASCII and v4.1 ASCII read; v4.1 ASCII written (v2.2 on request).
//            Physical tag -> integer kLabel, elementary tag (in 4.1 the entity tag, the physical
//            tag being the entity's first in $Entities) -> integer kRegion, for tets (T) and
//            triangles (F). Points and lines are skipped; other element types are rejected.
// An integer reference column that is zero everywhere (MEDIT references, Gmsh tags, TetGen regions and
// markers) carries nothing and is not turned into an attribute; writers write 0 for a missing one.
#pragma once

#include "vesalius/core/mesh.h"

#include <charconv>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vesalius::io {

// Coordinate system named by a "SPACE=..." tag.
enum class SpaceTag { kNone, kLps, kRas };

// The tag found in a piece of header text: SPACE=RAS wins over SPACE=LPS; kNone when neither appears.
inline SpaceTag findSpaceTag(std::string_view headerText) {
  if (headerText.find("SPACE=RAS") != std::string_view::npos) return SpaceTag::kRas;
  if (headerText.find("SPACE=LPS") != std::string_view::npos) return SpaceTag::kLps;
  return SpaceTag::kNone;
}

// Negates x and y of every row of V (#V by 3): RAS <-> LPS. A rotation, so orientation is kept.
inline void flipRasLps(MatrixX3d& V) { V.leftCols<2>() *= -1.0; }

// Swaps the last two vertices of every tet with negative signed volume; returns how many were swapped.
inline int orientTetsPositively(const MatrixX3d& V, MatrixX4i& T) {
  const Eigen::VectorXd volumes = tetVolumes(V, T);
  int swapped = 0;
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    if (volumes(t) < 0) {
      std::swap(T(t, 2), T(t, 3));
      ++swapped;
    }
  return swapped;
}

// The mesh with vertices of exactly equal coordinates (-0.0 equal to 0.0) made one, numbered in the order
// of their first occurrence; F is renumbered, UV/FUV and face attributes are kept. A vertex attribute
// is kept when the merged points agree on it and dropped when they do not (normals of a cube written per
// face: per-corner values no single vertex value can stand for). A mesh without such vertices comes
// back unchanged. readTriMesh applies it to an open surface whose boundary it shortens: files such as
// Slicer's cube.vtk store each face with its own copies of the corners, which would otherwise be read as
// separate open pieces. A closed surface keeps its vertices (their numbers may carry meaning).
TriMesh mergeCoincidentVertices(const TriMesh& mesh);

// STL, ASCII or binary. Binary is recognised by its size (84 + 50 n bytes for n triangles in the
// header), even when it begins with "solid"; anything else starting with "solid" is ASCII.
TriMesh parseStl(std::string_view bytes, const std::string& source);
// Binary STL (80-byte header with "SPACE=LPS", float32 coordinates, facet normals computed). Throws
// BadInput naming `destination` for a coordinate beyond float32's range (ASCII STL keeps doubles).
std::string formatStlBinary(const TriMesh& mesh, const std::string& destination = "");
// ASCII STL, "solid SPACE=LPS", coordinates with full double precision.
std::string formatStlAscii(const TriMesh& mesh);

// Wavefront OBJ (see the attribute table above).
TriMesh parseObj(std::string_view text, const std::string& source);
std::string formatObj(const TriMesh& mesh);

// TetGen .node/.ele/.face. `faceText` may be empty (no .face file). Indices are 0- or 1-based as the
// first node index of the .node file says. `source` is the path without extension; messages name
// source + ".node", ".ele" or ".face".
TetMesh parseTetGen(std::string_view nodeText, std::string_view eleText, std::string_view faceText,
                    const std::string& source);
struct TetGenFiles {
  std::string node, ele, face;  // face is empty when the mesh has no F
};
// 1-based indices, as TetGen writes by default.
TetGenFiles formatTetGen(const TetMesh& mesh);

// MEDIT .mesh (ASCII, MeshVersionFormatted 1 or 2, Dimension 3): Vertices, Tetrahedra, Triangles;
// Edges, Corners, Ridges, Required*, Normals and Tangents sections are skipped; Quadrilaterals,
// Hexahedra, Prisms and unknown sections are rejected.
TetMesh parseMedit(std::string_view text, const std::string& source);
std::string formatMedit(const TetMesh& mesh);

// Gmsh .msh v1, v2 ASCII or v4.1 ASCII (binary files and v4.0 are rejected with a message saying so).
TetMesh parseGmsh(std::string_view text, const std::string& source);
enum class GmshVersion { k22, k41 };
// Gmsh ASCII: nodes, then triangles (F), then tets (T), each with physical and elementary tags. 4.1,
// Gmsh's own default, unless asked for 2.2 (for readers that predate Gmsh 4). In 4.1 the elementary
// tag names an entity: one per (elementary, physical) pair; elements without kRegion get the entity of
// their physical tag (so they read back with kRegion equal to kLabel, the unlabelled ones with the
// largest label + 1), and elementary tags that are not positive or span two physical groups are
// renumbered 1, 2, ...
std::string formatGmsh(const TetMesh& mesh, GmshVersion version = GmshVersion::k41);

// Small pieces the format files share.
namespace detail {

// Appends the shortest decimal text that reads back as exactly `value` (writers lose no precision).
inline void appendReal(std::string& out, double value) {
  char buffer[32];
  out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

inline void appendInteger(std::string& out, long long value) {
  char buffer[24];
  out.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

// The matrix (#rows by `columns`) of values collected row after row, as the parsers read them.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> fromRows(const std::vector<Scalar>& values,
                                                                Eigen::Index columns) {
  using RowMajor = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const Eigen::Index rows = columns > 0 ? static_cast<Eigen::Index>(values.size()) / columns : 0;
  return Eigen::Map<const RowMajor>(values.data(), rows, columns);
}

// An integer reference column as an attribute, unless it is zero everywhere (then it carries nothing).
template <class Vector>
void addReferenceColumn(AttributeSet& attributes, const std::string& name, const Vector& values) {
  bool anyNonZero = false;
  for (int value : values) anyNonZero = anyNonZero || value != 0;
  if (anyNonZero) attributes.integer[name] = Eigen::Map<const Eigen::VectorXi>(values.data(), values.size());
}

// The integer attribute `name` if present with `rows` rows, else zeros (what writers put in a
// reference column the mesh does not have).
inline Eigen::VectorXi referenceColumn(const AttributeSet& attributes, const std::string& name, Eigen::Index rows) {
  const auto found = attributes.integer.find(name);
  return found != attributes.integer.end() && found->second.rows() == rows ? found->second
                                                                          : Eigen::VectorXi::Zero(rows);
}

}  // namespace detail

}  // namespace vesalius::io
