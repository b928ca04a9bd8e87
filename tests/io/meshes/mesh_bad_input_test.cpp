// Broken mesh files (testdata/bad/mesh_*, see SOURCE.md there): each must give one BadInput line that
// names the file and the problem, never a crash. Also the writers' "nothing is lost" rules.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"

#include "expect_bad_input.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

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
    {"mesh_short_point_data.vtk", false, "Possible mismatch of datasize with declaration"},
    {"mesh_image.vtk", false, "holds VTK structured_points"},
    {"mesh_truncated.vtp", false, "Error parsing XML in stream at line 15"},
    {"mesh_truncated.ply", false, "PLY data ends early, in vertex 4 of 4"},
    {"mesh_short_row.ply", false, "PLY vertex 4 has too few values on its line"},
    {"mesh_no_y.ply", false, "PLY vertices have no 'y' property"},
    {"mesh_faces_without_indices.ply", false, "PLY file has no faces with a 'vertex_indices' list"},
    {"mesh_end_header_glued.ply", false, "not a PLY file (expected 'ply' ... 'end_header')"},
    {"mesh_nul_in_line.ply", false, "PLY face 1 has too few values on its line"},
    {"mesh_vertex_twice.ply", false, "PLY element 'vertex' is declared twice"},
    {"mesh_missing_node.ele", true, "mesh_missing_node.ele: line 3: node 9 does not exist"},
    {"mesh_no_vertices.mesh", true, "no 'Vertices' section"},
    {"mesh_hexahedra.mesh", true, "section 'Hexahedra' is not supported"},
    {"mesh_bad_node_index.msh", true, "line 10: bad node number 'x'"},
    {"mesh_gmsh41_truncated.msh", true, "mesh_gmsh41_truncated.msh: line 100: file ends in node coordinates"},
    {"mesh_gmsh41_binary.msh", true, "line 2: binary Gmsh files are not supported (save as ASCII"},
    {"mesh_hexahedron.vtu", true, "cell 0 is a hexahedron (VTK cell type 12); only tetrahedra are supported"},
    {"mesh_hexahedron.vtk", true, "cell 0 is a hexahedron"},
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
