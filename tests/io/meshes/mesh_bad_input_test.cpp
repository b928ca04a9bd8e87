// Broken mesh files (testdata/bad/mesh_*, see SOURCE.md there): each must give one BadInput line that
// names the file and the problem, never a crash. Also the writers' "nothing is lost" rules.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"

#include "expect_bad_input.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

std::string badFile(const std::string& name) { return std::string(VESALIUS_TESTDATA) + "/bad/" + name; }

struct BadCase {
  const char* file;
  bool tetMesh;
  const char* expected;  // part of the message
};

const BadCase kCases[] = {
    {"mesh_truncated_binary.stl", false, "12 triangles should have 684 bytes, but has 351 (truncated)"},
    {"mesh_too_short.stl", false, "too short"},
    {"mesh_nan_vertex.stl", false, "line 12: bad vertex coordinate 'nan'"},
    {"mesh_nan_vertex_binary.stl", false, "triangle 1 has a non-finite coordinate"},
    {"mesh_face_out_of_range.obj", false, "line 5: vertex index 9 out of range (3 defined so far)"},
    {"mesh_mixed_uv.obj", false, "has texture coordinates but the face on line 7 has none"},
    {"mesh_strips.vtk", false, "triangle strips are not supported"},
    {"mesh_short_point_data.vtk", false, "the file ends after 2 of 3 values of SCALARS 's'"},
    {"mesh_image.vtk", false, "holds VTK structured_points"},
    {"mesh_truncated.vtp", false, "Error parsing XML in stream at line 15"},
    {"mesh_huge_components.vtp", false, "NumberOfComponents=\"11111111111111111113\" is not a component count"},
    {"mesh_truncated.ply", false, "PLY data ends early, in vertex 4 of 4"},
    {"mesh_short_row.ply", false, "PLY vertex 4 has too few values on its line"},
    {"mesh_no_y.ply", false, "PLY vertices have no 'y' property"},
    {"mesh_faces_without_indices.ply", false, "PLY file has no faces with a 'vertex_indices' list"},
    {"mesh_end_header_glued.ply", false, "not a PLY file (expected 'ply' ... 'end_header')"},
    {"mesh_nul_in_line.ply", false, "PLY face 1 has too few values on its line"},
    {"mesh_vertex_twice.ply", false, "PLY element 'vertex' is declared twice"},
    {"mesh_empty_header_line.ply", false, "PLY header line 4 is empty"},
    {"mesh_element_without_properties.ply", false, "PLY element 'material' has no properties"},
    {"mesh_vertex_index_in_data.ply", false, "PLY vertex 2 has too few values on its line"},
    {"mesh_face_extra_list.ply", false, "PLY face property 'other' is a list, which VTK's PLY reader cannot skip"},
    {"mesh_element_before_vertices.ply", false,
     "PLY element 'material' comes before the vertices or faces, which VTK's PLY reader does not skip"},
    {"mesh_property_twice.ply", false, "PLY face property 'vertex_indices' is declared twice"},
    {"mesh_last_line_unended.ply", false, "PLY face 4 is on a line without a newline at its end"},
    {"mesh_polygon_bad_number.vtk", false, "line 12: bad number '1?3' in POLYGONS values"},
    {"mesh_missing_node.ele", true, "mesh_missing_node.ele: line 3: node 9 does not exist"},
    {"mesh_no_vertices.mesh", true, "no 'Vertices' section"},
    {"mesh_hexahedra.mesh", true, "section 'Hexahedra' is not supported"},
    {"mesh_bad_node_index.msh", true, "line 10: bad node number 'x'"},
    {"mesh_gmsh41_truncated.msh", true, "mesh_gmsh41_truncated.msh: line 100: file ends in node coordinates"},
    {"mesh_gmsh41_binary.msh", true, "line 2: binary Gmsh files are not supported (save as ASCII"},
    {"mesh_hexahedron.vtu", true, "cell 0 is a hexahedron (VTK cell type 12); only tetrahedra are supported"},
    {"mesh_hexahedron.vtk", true, "line 10: CELL_TYPES cell 1 is a hexahedron (VTK cell type 12); only tetrahedra"},
    {"mesh_tets_cells_beyond_file.vtk", true, "line 7: cell list size 1000000000 is out of range"},
    {"mesh_tets_cell_runs_past.vtk", true, "line 7: CELLS cell 2 runs past the 10 values declared"},
    {"mesh_tets_index.vtk", true, "line 9: CELLS cell 2 refers to point 100000000 of 5"},
    {"mesh_tets_types_short.vtk", true, "line 10: CELL_TYPES declares 1 cells, CELLS 2"},
    {"mesh_tets_type_266.vtk", true, "line 12: CELL_TYPES cell 2 is of VTK cell type 266, which VTK does not know"},
    {"mesh_tets_polyhedron.vtk", true, "line 12: CELL_TYPES cell 2 is a polyhedron (VTK cell type 42)"},
    {"mesh_tets_triangle_cell.vtk", true, "line 7: CELLS cell 2 has 3 points; a tetrahedron has 4"},
    {"mesh_strips.vtk", true, "holds VTK polydata, not an unstructured grid"},
    {"no_such_mesh.obj", false, "cannot open"},
    {"no_such_mesh.vtu", true, "cannot open"},
};

class BadMeshFile : public testing::TestWithParam<BadCase> {};

TEST_P(BadMeshFile, ThrowsOneLineNamingTheFile) {
  const BadCase& c = GetParam();
  const std::string path = badFile(c.file);
  test::expectOneLineBadInput(path, c.expected, [&] {
    if (c.tetMesh)
      readTetMesh(path);
    else
      readTriMesh(path);
  });
}

INSTANTIATE_TEST_SUITE_P(Meshes, BadMeshFile, testing::ValuesIn(kCases),
                         [](const testing::TestParamInfo<BadCase>& info) {
                           std::string name = std::to_string(info.index) + "_" + info.param.file;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

TEST(BadMeshFile, UnknownExtensions) {
  EXPECT_THROW(readTriMesh(badFile("mesh_gmsh41_binary.msh")), BadInput);
  EXPECT_THROW(readTetMesh(badFile("mesh_face_out_of_range.obj")), BadInput);
  EXPECT_FALSE(meshFileKind("scan.nii.gz").has_value());
  EXPECT_EQ(meshFileKind(badFile("mesh_hexahedron.vtk")), MeshKind::kTetrahedral);
  EXPECT_EQ(meshFileKind(badFile("mesh_strips.vtk")), MeshKind::kSurface);
  EXPECT_THROW(meshFileKind(badFile("mesh_image.vtk")), BadInput);
}

// Legacy VTK polydata of one convex polygon with `corners` corners on a circle, written as vtkDataReader
// reads it: ASCII or binary (big-endian), with the cell layout of version 4.2 (each cell's size, then its
// indices) or 5.1 (OFFSETS, CONNECTIVITY). `lastIndex` replaces the polygon's last point index, `badNumber`
// (ASCII) the first number of its cell list, and a binary file is cut `cut` bytes short.
struct LegacyPolygon {
  int corners = 3;
  bool binary = false, v51 = false;
  long long lastIndex = -1;
  std::string badNumber;
  std::size_t cut = 0;
};

std::string bigEndian(std::uint64_t value, int bytes) {
  std::string out;
  for (int k = bytes - 1; k >= 0; --k) out += static_cast<char>(value >> (8 * k) & 0xff);
  return out;
}

std::string floatBigEndian(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, 4);
  return bigEndian(bits, 4);
}

std::string legacyPolygon(const LegacyPolygon& p) {
  const int n = p.corners;
  std::vector<long long> ids(static_cast<std::size_t>(n));
  std::iota(ids.begin(), ids.end(), 0LL);
  if (p.lastIndex >= 0) ids.back() = p.lastIndex;
  std::ostringstream out;
  out << "# vtk DataFile Version " << (p.v51 ? "5.1" : "4.2") << "\npolygon\n" << (p.binary ? "BINARY" : "ASCII")
      << "\nDATASET POLYDATA\nPOINTS " << n << " float\n";
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i) {
    const float xyz[3] = {float(10 * std::cos(2 * pi * i / n)), float(10 * std::sin(2 * pi * i / n)), 1.0f};
    for (float c : xyz) out << (p.binary ? floatBigEndian(c) : std::to_string(c) + " ");
  }
  out << "\n";
  // Integers as the layout writes them: 4 bytes (4.2) or vtktypeint64 (5.1).
  const auto integers = [&](const std::vector<long long>& values, int bytes, bool firstMayBeBad) {
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (p.binary)
        out << bigEndian(static_cast<std::uint64_t>(values[i]), bytes);
      else if (firstMayBeBad && i == 0 && !p.badNumber.empty())
        out << p.badNumber << " ";
      else
        out << values[i] << " ";
    }
    out << "\n";
  };
  if (p.v51) {
    out << "POLYGONS 2 " << n << "\nOFFSETS vtktypeint64\n";
    integers({0, n}, 8, false);
    out << "CONNECTIVITY vtktypeint64\n";
    integers(ids, 8, true);
  } else {
    out << "POLYGONS 1 " << n + 1 << "\n";
    ids.insert(ids.begin(), n);
    integers(ids, 4, true);
  }
  std::string text = out.str();
  return text.substr(0, text.size() - std::min(p.cut, text.size()));
}

void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Each layout and polygon size: the polygon reads as its fan of triangles; an index beyond the points, a
// malformed number and a cut binary list are refused with the line of the problem, before VTK reads them.
TEST(BadMeshFile, LegacyVtkPolygonLists) {
  const std::string folder = std::string(VESALIUS_TEST_OUTPUT) + "/legacy-vtk";
  fs::create_directories(folder);
  for (const bool v51 : {false, true})
    for (const bool binary : {false, true})
      for (const int n : {3, 5, 12}) {
        const std::string name = folder + "/polygon" + std::to_string(n) + (v51 ? "_v51" : "_v42") +
                                 (binary ? "_binary" : "_ascii");
        LegacyPolygon p;
        p.corners = n;
        p.binary = binary;
        p.v51 = v51;
        writeFile(name + ".vtk", legacyPolygon(p));
        const TriMesh mesh = readTriMesh(name + ".vtk");
        ASSERT_EQ(mesh.V.rows(), n) << name;
        ASSERT_EQ(mesh.F.rows(), n - 2) << name;
        for (int k = 0; k + 2 < n; ++k) {
          EXPECT_EQ(mesh.F(k, 0), 0) << name;
          EXPECT_EQ(mesh.F(k, 1), k + 1) << name;
          EXPECT_EQ(mesh.F(k, 2), k + 2) << name;
        }
        std::cout << name << ": " << mesh.F.rows() << " triangles\n";

        // In ASCII the cell list is the last line: line 8 (4.2) or 11 (5.1, after the offsets).
        const std::string listLine = "line " + std::to_string(v51 ? 11 : 8) + ": ";
        p.lastIndex = n;
        writeFile(name + "_index.vtk", legacyPolygon(p));
        test::expectOneLineBadInput(name + "_index.vtk",
                                    "POLYGONS cell 1 refers to point " + std::to_string(n) + " of " + std::to_string(n),
                                    [&] { readTriMesh(name + "_index.vtk"); });
        p.lastIndex = -1;
        if (binary) {
          p.cut = 3;
          writeFile(name + "_cut.vtk", legacyPolygon(p));
          test::expectOneLineBadInput(name + "_cut.vtk", v51 ? "POLYGONS connectivity take" : "POLYGONS values take",
                                      [&] { readTriMesh(name + "_cut.vtk"); });
          test::expectOneLineBadInput(name + "_cut.vtk", "but only", [&] { readTriMesh(name + "_cut.vtk"); });
        } else if (v51) {
          test::expectOneLineBadInput(name + "_index.vtk", listLine, [&] { readTriMesh(name + "_index.vtk"); });
          p.badNumber = "0x";
          writeFile(name + "_number.vtk", legacyPolygon(p));
          test::expectOneLineBadInput(name + "_number.vtk", listLine + "bad number '0x' in POLYGONS connectivity",
                                      [&] { readTriMesh(name + "_number.vtk"); });
        } else {
          test::expectOneLineBadInput(name + "_index.vtk", listLine, [&] { readTriMesh(name + "_index.vtk"); });
          std::string text = legacyPolygon(p);
          const std::size_t list = text.rfind('\n', text.size() - 2) + 1;
          text.replace(list, std::to_string(n).size(), "3\xe6");
          writeFile(name + "_number.vtk", text);
          test::expectOneLineBadInput(name + "_number.vtk", listLine + "bad number '3?' in POLYGONS values",
                                      [&] { readTriMesh(name + "_number.vtk"); });
        }
      }
}

// Legacy VTK unstructured grid of two tetrahedra sharing a face, written as vtkDataReader reads it: ASCII or
// binary (big-endian), cells in the layout of version 4.2 or 5.1 (OFFSETS, CONNECTIVITY), then CELL_TYPES.
// `lastIndex` replaces the second tetrahedron's last point index, `types` (when not empty) the cell types,
// and a binary file is cut `cut` bytes short.
struct LegacyTets {
  bool binary = false, v51 = false;
  long long lastIndex = -1;
  std::vector<long long> types;
  std::size_t cut = 0;
};

std::string legacyTets(const LegacyTets& p) {
  std::ostringstream out;
  out << "# vtk DataFile Version " << (p.v51 ? "5.1" : "4.2") << "\ntwo tetrahedra\n" << (p.binary ? "BINARY" : "ASCII")
      << "\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 float\n";
  const float xyz[15] = {0, 0, 0, 10, 0, 0, 0, 10, 0, 0, 0, 10, 10, 10, 10};
  for (float c : xyz) out << (p.binary ? floatBigEndian(c) : std::to_string(c) + " ");
  out << "\n";
  const auto integers = [&](const std::vector<long long>& values, int bytes) {
    for (long long v : values) out << (p.binary ? bigEndian(static_cast<std::uint64_t>(v), bytes) : std::to_string(v) + " ");
    out << "\n";
  };
  std::vector<long long> ids{0, 1, 2, 3, 1, 2, 3, p.lastIndex >= 0 ? p.lastIndex : 4};
  if (p.v51) {
    out << "CELLS 3 8\nOFFSETS vtktypeint64\n";
    integers({0, 4, 8}, 8);
    out << "CONNECTIVITY vtktypeint64\n";
    integers(ids, 8);
  } else {
    out << "CELLS 2 10\n";
    ids.insert(ids.begin() + 4, 4);
    ids.insert(ids.begin(), 4);
    integers(ids, 4);
  }
  const std::vector<long long> types = p.types.empty() ? std::vector<long long>{10, 10} : p.types;
  out << "CELL_TYPES " << types.size() << "\n";
  integers(types, 4);
  std::string text = out.str();
  return text.substr(0, text.size() - std::min(p.cut, text.size()));
}

// Each layout, ASCII and binary: the two tetrahedra read; a point index beyond POINTS, fewer cell types than
// cells, a type VTK would truncate to a tetrahedron (266 = 256 + 10) and a cut binary file are refused
// before vtkUnstructuredGridReader reads them.
TEST(BadMeshFile, LegacyVtkTetrahedra) {
  const std::string folder = std::string(VESALIUS_TEST_OUTPUT) + "/legacy-vtk-tets";
  fs::create_directories(folder);
  for (const bool v51 : {false, true})
    for (const bool binary : {false, true}) {
      const std::string name = folder + "/tets" + (v51 ? "_v51" : "_v42") + (binary ? "_binary" : "_ascii");
      LegacyTets p;
      p.binary = binary;
      p.v51 = v51;
      writeFile(name + ".vtk", legacyTets(p));
      const TetMesh mesh = readTetMesh(name + ".vtk");
      ASSERT_EQ(mesh.V.rows(), 5) << name;
      ASSERT_EQ(mesh.T.rows(), 2) << name;
      for (int t = 0; t < 2; ++t) {
        std::vector<int> corners{mesh.T(t, 0), mesh.T(t, 1), mesh.T(t, 2), mesh.T(t, 3)};
        std::sort(corners.begin(), corners.end());
        EXPECT_EQ(corners, (std::vector<int>{t, t + 1, t + 2, t + 3})) << name << " tetrahedron " << t;
      }
      std::cout << name << ": " << mesh.T.rows() << " tetrahedra\n";

      p.lastIndex = 5;
      writeFile(name + "_index.vtk", legacyTets(p));
      test::expectOneLineBadInput(name + "_index.vtk", "CELLS cell 2 refers to point 5 of 5",
                                  [&] { readTetMesh(name + "_index.vtk"); });
      p.lastIndex = -1;
      p.types = {10};
      writeFile(name + "_types.vtk", legacyTets(p));
      test::expectOneLineBadInput(name + "_types.vtk", "CELL_TYPES declares 1 cells, CELLS 2",
                                  [&] { readTetMesh(name + "_types.vtk"); });
      p.types = {10, 266};
      writeFile(name + "_266.vtk", legacyTets(p));
      test::expectOneLineBadInput(name + "_266.vtk", "CELL_TYPES cell 2 is of VTK cell type 266",
                                  [&] { readTetMesh(name + "_266.vtk"); });
      p.types.clear();
      if (binary) {
        p.cut = 5;  // into the cell types
        writeFile(name + "_cut.vtk", legacyTets(p));
        test::expectOneLineBadInput(name + "_cut.vtk", "2 cell types take 2 x 4 bytes, but only",
                                    [&] { readTetMesh(name + "_cut.vtk"); });
      }
    }
  // CELLS and CELL_TYPES go together, once each (vtkUnstructuredGridReader pairs a second list with the
  // first's types).
  const std::string ascii = legacyTets({});
  const std::size_t types = ascii.find("CELL_TYPES");
  const struct {
    std::string name, text, expected;
  } sections[] = {
      {"cells_only", ascii.substr(0, types), "line 7: CELLS without CELL_TYPES"},
      {"types_only", ascii.substr(0, ascii.find("CELLS")) + ascii.substr(types), "line 7: CELL_TYPES without CELLS"},
      {"cells_twice", ascii.substr(0, types) + ascii.substr(ascii.find("CELLS")), "line 9: a second CELLS section"},
      {"types_twice", ascii + ascii.substr(types), "line 11: a second CELL_TYPES section"}};
  for (const auto& c : sections) {
    const std::string path = folder + "/tets_" + c.name + ".vtk";
    writeFile(path, c.text);
    test::expectOneLineBadInput(path, c.expected, [&] { readTetMesh(path); });
  }
}

// Attributes after the geometry, as vtkDataReader reads them: POINT_DATA then CELL_DATA arrays read onto
// the vertices and cells. Declared sizes the file cannot hold (a SCALARS line with billions of components,
// colours, a lookup table) are refused before VTK allocates them; so are counts other than the points and
// cells (VTK checks only the first), a texture dimension VTK does not read, an unknown attribute and the
// run of spaces VTK would loop on. METADATA blocks are skipped. Polygons and tetrahedra, ASCII and binary.
TEST(BadMeshFile, LegacyVtkAttributes) {
  const std::string folder = std::string(VESALIUS_TEST_OUTPUT) + "/legacy-vtk-attributes";
  fs::create_directories(folder);
  for (const bool tets : {false, true})
    for (const bool binary : {false, true}) {
      LegacyPolygon polygon;
      polygon.corners = 5;
      polygon.binary = binary;
      LegacyTets grid;
      grid.binary = binary;
      // Five points either way; the polygon is one cell, the grid two.
      const std::string geometry = tets ? legacyTets(grid) : legacyPolygon(polygon);
      const int points = 5, cells = tets ? 2 : 1;
      const auto ints = [&](int count, int first) {
        std::string out;
        for (int i = 0; i < count; ++i)
          out += binary ? bigEndian(static_cast<std::uint32_t>(first + i), 4) : std::to_string(first + i) + " ";
        return out + "\n";
      };
      const auto floats = [&](int count, float first) {
        std::string out;
        for (int i = 0; i < count; ++i) out += binary ? floatBigEndian(first + i) : std::to_string(first + i) + " ";
        return out + "\n";
      };
      // METADATA blocks as vtkDataWriter writes them: information keys after the points, component names.
      const std::string information =
          "METADATA\nINFORMATION 2\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 17.3\n"
          "NAME L2_NORM_FINITE_RANGE LOCATION vtkDataArray\nDATA 2 0 17.3\n\n";
      const std::size_t cellsAt = geometry.find(tets ? "CELLS" : "POLYGONS");
      const std::string good = "POINT_DATA 5\nSCALARS bone int 1\nLOOKUP_TABLE default\n" + ints(points, 7) +
                               "VECTORS shift float\n" + floats(3 * points, 0.5f) +
                               "SCALARS pair float 2\nLOOKUP_TABLE default\n" + floats(2 * points, 1.0f) +
                               "METADATA\nCOMPONENT_NAMES\nfirst\nsecond\n\nCELL_DATA " + std::to_string(cells) +
                               "\nSCALARS weight float\nLOOKUP_TABLE default\n" + floats(cells, 2.5f);
      const std::string name = folder + (tets ? "/tets" : "/polygon") + (binary ? "_binary" : "_ascii");
      writeFile(name + ".vtk", geometry.substr(0, cellsAt) + information + geometry.substr(cellsAt) + good);
      const auto read = [&](const std::string& path) {
        if (tets) {
          const TetMesh mesh = readTetMesh(path);
          return std::make_pair(mesh.vertexAttributes, mesh.tetAttributes);
        }
        const TriMesh mesh = readTriMesh(path);
        return std::make_pair(mesh.vertexAttributes, mesh.faceAttributes);
      };
      const auto [vertex, cell] = read(name + ".vtk");
      ASSERT_TRUE(vertex.integer.count("bone")) << name;
      for (int i = 0; i < points; ++i) EXPECT_EQ(vertex.integer.at("bone")(i), 7 + i) << name;
      ASSERT_TRUE(vertex.real.count("shift")) << name;
      EXPECT_EQ(vertex.real.at("shift").cols(), 3) << name;
      EXPECT_DOUBLE_EQ(vertex.real.at("shift")(points - 1, 2), 0.5 + 3 * points - 1) << name;
      ASSERT_TRUE(vertex.real.count("pair")) << name;
      EXPECT_EQ(vertex.real.at("pair").cols(), 2) << name;
      EXPECT_DOUBLE_EQ(vertex.real.at("pair")(points - 1, 1), 1.0 + 2 * points - 1) << name;
      ASSERT_TRUE(cell.real.count("weight")) << name;
      EXPECT_DOUBLE_EQ(cell.real.at("weight")(0, 0), 2.5) << name;
      std::cout << name << ": bone, shift, pair and weight read past two METADATA blocks\n";

      const struct {
        std::string name, attributes, expected;
      } bad[] = {
          {"components", "POINT_DATA 5\nSCALARS bone int 444444444444441\nLOOKUP_TABLE default\n" + ints(points, 0),
           "number of SCALARS components 444444444444441 is out of range"},
          {"components_fit", "POINT_DATA 5\nSCALARS bone int 100000000\nLOOKUP_TABLE default\n" + ints(points, 0),
           "SCALARS 'bone' declares 100000000 x 5 values, more than the file can hold"},
          {"no_table", "POINT_DATA 5\nSCALARS bone int 1\n" + ints(points, 0), "expected LOOKUP_TABLE"},
          {"colours", "POINT_DATA 5\nCOLOR_SCALARS rgb 2000000000\n" + floats(points, 0),
           "COLOR_SCALARS 'rgb' declares 2000000000 x 5 values"},
          {"table", "POINT_DATA 5\nLOOKUP_TABLE grey 2000000000\n" + floats(4, 0),
           "LOOKUP_TABLE 'grey' declares 2000000000 colours"},
          {"point_count", "POINT_DATA 4\nSCALARS bone int 1\nLOOKUP_TABLE default\n" + ints(4, 0),
           "POINT_DATA declares 4 points, the file has 5"},
          {"later_count", "POINT_DATA 5\nCELL_DATA 9000000000000\nSCALARS w float\nLOOKUP_TABLE default\n" +
                              floats(cells, 0),
           "CELL_DATA declares 9000000000000 cells, the file has " + std::to_string(cells)},
          {"texture", "POINT_DATA 5\nTEXTURE_COORDINATES uv 4 float\n" + floats(4 * points, 0),
           "texture coordinate dimension 4 is out of range [1, 3]"},
          {"unknown", "POINT_DATA 5\nCURVATURE k float\n" + floats(points, 0), "unknown attribute 'CURVATURE'"},
          // vtkDataReader would look for the end of these spaces for ever.
          {"spaces", "POINT_DATA 5\nSCALARS bone int 1\nLOOKUP_TABLE default\n" + ints(points, 0) +
                         std::string(300, ' ') + "\n",
           "256 or more spaces after the values of SCALARS 'bone'"}};
      for (const auto& c : bad) {
        const std::string path = name + "_" + c.name + ".vtk";
        writeFile(path, geometry + c.attributes);
        test::expectOneLineBadInput(path, c.expected, [&] { read(path); });
      }
    }
}

// A PLY polygon whose last line lacks its newline is refused; with it, it reads, at each size.
TEST(BadMeshFile, PlyLastLineNeedsItsNewline) {
  const std::string folder = std::string(VESALIUS_TEST_OUTPUT) + "/ply-newline";
  fs::create_directories(folder);
  for (const int n : {3, 5, 12}) {
    std::ostringstream text;
    text << "ply\nformat ascii 1.0\nelement vertex " << n
         << "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < n; ++i) text << std::cos(6.283 * i / n) << " " << std::sin(6.283 * i / n) << " 0\n";
    text << n;
    for (int i = 0; i < n; ++i) text << " " << i;
    const std::string path = folder + "/polygon" + std::to_string(n) + ".ply";
    writeFile(path, text.str());
    test::expectOneLineBadInput(path, "PLY face 1 is on a line without a newline at its end",
                                [&] { readTriMesh(path); });
    writeFile(path, text.str() + "\n");
    EXPECT_EQ(readTriMesh(path).F.rows(), n - 2) << path;
  }
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TriMesh triangle() {
  TriMesh mesh;
  mesh.V.resize(3, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  mesh.F.resize(1, 3);
  mesh.F << 0, 1, 2;
  return mesh;
}

TEST(MeshWriters, KeepExistingOutputUnlessForced) {
  const std::string folder = std::string(VESALIUS_TEST_OUTPUT) + "/writers";
  fs::create_directories(folder);
  for (const char* ext : {".obj", ".stl", ".vtp"}) {
    const std::string path = folder + "/kept" + ext;
    fs::remove(path);
    writeTriMesh(path, triangle());
    const std::string before = slurp(path);
    TriMesh moved = triangle();
    moved.V(0, 2) = 5;
    EXPECT_THROW(writeTriMesh(path, moved), UsageError) << ext;
    EXPECT_EQ(slurp(path), before) << ext;
    MeshWriteOptions force;
    force.force = true;
    writeTriMesh(path, moved, force);
    EXPECT_EQ(readTriMesh(path).V(0, 2), 5) << ext;
  }
  EXPECT_THROW(writeTriMesh(folder + "/mesh.xyz", triangle()), UsageError);
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 3);  // no temporaries left
}

TEST(MeshWriters, RefuseABrokenMesh) {
  TriMesh mesh = triangle();
  mesh.F(0, 2) = 7;
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/broken.obj";
  fs::create_directories(VESALIUS_TEST_OUTPUT);
  fs::remove(path);
  EXPECT_THROW(writeTriMesh(path, mesh), BadInput);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace vesalius::io
