// Real meshes from testdata/ read, written in every format, and read again (mesh_io.h): same counts,
// same corner coordinates (orientation included), same uv and attributes where the format carries them.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <iostream>
#include <map>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
const std::string kLiverSurface = kData + "/liver/liver-smooth.obj";
const std::string kLiverTets = kData + "/liver/liver.msh";
const std::string kGluteus = kData + "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl";
const std::string kPelvis = kData + "/skeleton-opensim/Geometry/r_pelvis.vtp";
const std::string kBody = kData + "/body/base.obj";

constexpr double kFloatEpsilon = 1.2e-7;  // float32 relative rounding (2^-23)

std::string output(const std::string& name) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / "roundtrip";
  fs::create_directories(folder);
  return (folder / name).string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void spit(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

MeshWriteOptions options(bool binary) {
  MeshWriteOptions o;
  o.force = true;
  o.binary = binary;
  return o;
}

// What a surface format keeps.
struct SurfaceFormat {
  const char* ext;
  bool binary;
  bool floatCoordinates;  // float32 on disk
  bool uv;                // per-corner uv (with seams)
  bool vertexUv;          // uv when each vertex has one
  bool attributes;        // all attributes (OBJ keeps "group" only)
};

const SurfaceFormat kSurfaceFormats[] = {
    {".stl", true, true, false, false, false},   {".stl", false, false, false, false, false},
    {".obj", false, false, true, true, false},   {".ply", true, true, false, true, false},
    {".ply", false, true, false, true, false},   {".vtk", true, false, true, true, true},
    {".vtk", false, false, true, true, true},     {".vtp", true, false, true, true, true},
    {".vtp", false, false, true, true, true}};

std::string formatName(const SurfaceFormat& f) { return std::string(f.ext) + (f.binary ? " binary" : " ascii"); }

TriMesh roundTrip(const TriMesh& mesh, const std::string& name, const SurfaceFormat& f) {
  const std::string path = output(name + (f.binary ? "-binary" : "-ascii") + f.ext);
  writeTriMesh(path, mesh, options(f.binary));
  return readTriMesh(path);
}

// Distinct coordinates used by triangles: the vertex count an STL file gives back.
std::size_t distinctCorners(const TriMesh& mesh) {
  std::set<std::tuple<double, double, double>> points;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const Eigen::RowVector3d p = mesh.V.row(mesh.F(f, c));
      points.emplace(p(0), p(1), p(2));
    }
  return points.size();
}

void expectSameCorners(const TriMesh& a, const TriMesh& b, double tolerance) {
  ASSERT_EQ(a.F.rows(), b.F.rows());
  double worst = 0;
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, (a.V.row(a.F(f, c)) - b.V.row(b.F(f, c))).cwiseAbs().maxCoeff());
  EXPECT_LE(worst, tolerance);
}

void expectSameCornerUv(const TriMesh& a, const TriMesh& b, double tolerance) {
  ASSERT_EQ(b.FUV.rows(), a.F.rows());
  double worst = 0;
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, (a.UV.row(a.FUV(f, c)) - b.UV.row(b.FUV(f, c))).cwiseAbs().maxCoeff());
  EXPECT_LE(worst, tolerance);
}

void expectSameAttributes(const AttributeSet& a, const AttributeSet& b) {
  ASSERT_EQ(a.integer.size(), b.integer.size());
  for (const auto& [name, values] : a.integer) EXPECT_EQ(b.integer.at(name), values) << name;
  ASSERT_EQ(a.real.size(), b.real.size());
  // 1e-9: ASCII VTK legacy files keep 11 significant digits.
  for (const auto& [name, values] : a.real) EXPECT_TRUE(b.real.at(name).isApprox(values, 1e-9)) << name;
}

void expectSurfaceRoundTrip(const TriMesh& mesh, const std::string& name, const SurfaceFormat& f) {
  SCOPED_TRACE(name + " through " + formatName(f));
  const TriMesh read = roundTrip(mesh, name, f);
  const double scale = std::max(1.0, mesh.V.cwiseAbs().maxCoeff());
  EXPECT_EQ(read.V.rows(), std::string(f.ext) == ".stl" ? Eigen::Index(distinctCorners(mesh)) : mesh.V.rows());
  expectSameCorners(mesh, read, f.floatCoordinates ? kFloatEpsilon * scale : 1e-6);
  const bool seams = mesh.FUV.rows() > 0 && mesh.UV.rows() != mesh.V.rows();
  if (mesh.FUV.rows() > 0 && (seams ? f.uv : f.vertexUv))
    expectSameCornerUv(mesh, read, f.floatCoordinates ? kFloatEpsilon : 0.0);
  else
    EXPECT_EQ(read.FUV.rows(), 0);
  if (f.attributes) {
    expectSameAttributes(mesh.vertexAttributes, read.vertexAttributes);
    expectSameAttributes(mesh.faceAttributes, read.faceAttributes);
  } else if (std::string(f.ext) == ".obj" && mesh.faceAttributes.has("group")) {
    EXPECT_EQ(read.faceAttributes.integer.at("group"), mesh.faceAttributes.integer.at("group"));
  }
}

TEST(SurfaceFiles, LiverIsAClosedSurfaceWithoutUv) {
  const TriMesh liver = readTriMesh(kLiverSurface);
  EXPECT_EQ(liver.V.rows(), 2194);
  EXPECT_EQ(liver.F.rows(), 4384);
  EXPECT_EQ(liver.FUV.rows(), 0);  // the file has normals (vn) but no vt
  const TriMeshSummary s = summarize(liver);
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.components, 1);
  ASSERT_TRUE(s.closed);
  EXPECT_GT(*s.volume, 0);  // outward orientation
}

TEST(SurfaceFiles, GluteusMediusVolume) {
  const TriMesh muscle = readTriMesh(kGluteus);
  EXPECT_EQ(muscle.F.rows(), 30072);
  EXPECT_EQ(muscle.V.rows(), 15038);  // closed genus-0 surface: V = F / 2 + 2
  const TriMeshSummary s = summarize(muscle);
  ASSERT_TRUE(s.closed);
  EXPECT_EQ(s.components, 1);
  EXPECT_NEAR(*s.volume, 370078.3, 370.0);  // mm^3, measured (and by a separate script); 0.1 %
}

TEST(SurfaceFiles, PelvisVtp) {
  const TriMesh pelvis = readTriMesh(kPelvis);
  EXPECT_EQ(pelvis.V.rows(), 122);
  EXPECT_EQ(pelvis.F.rows(), 246);
}

TEST(SurfaceFiles, BodyQuadsUvAndGroups) {
  const TriMesh body = readTriMesh(kBody);
  EXPECT_EQ(body.V.rows(), 19158);
  EXPECT_EQ(body.F.rows(), 2 * 18486);  // quads, fan-triangulated
  EXPECT_EQ(body.UV.rows(), 21334);
  EXPECT_EQ(body.FUV.rows(), body.F.rows());
  const Eigen::VectorXi& group = body.faceAttributes.integer.at("group");
  EXPECT_EQ(group.maxCoeff() + 1, 139);  // groups with faces, numbered in order of their first face
  EXPECT_EQ(group(0), 0);
}

// A unit cube as vtkCubeSource makes it and Slicer's cube.vtk stores it: 24 points (each face its own 4
// corners), 6 quads, per-point normals and texture coordinates.
std::string perFaceCubeVtk(double side) {
  static const int kFaces[6][4][3] = {{{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
                                      {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
                                      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  static const int kNormals[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  std::ostringstream points, polygons, normals, uv;
  for (int f = 0; f < 6; ++f) {
    polygons << "4";
    for (int c = 0; c < 4; ++c) {
      for (int k = 0; k < 3; ++k) points << (kFaces[f][c][k] - 0.5) * side << (k < 2 ? " " : "\n");
      normals << kNormals[f][0] << " " << kNormals[f][1] << " " << kNormals[f][2] << "\n";
      uv << (c == 1 || c == 2) << " " << (c >= 2) << "\n";
      polygons << " " << 4 * f + c;
    }
    polygons << "\n";
  }
  return "# vtk DataFile Version 4.2\nvtk output\nASCII\nDATASET POLYDATA\nPOINTS 24 float\n" + points.str() +
         "POLYGONS 6 30\n" + polygons.str() + "POINT_DATA 24\nNORMALS Normals float\n" + normals.str() +
         "TEXTURE_COORDINATES TCoords 2 float\n" + uv.str();
}

TEST(SurfaceFiles, PointsDuplicatedPerFaceAreMerged) {
  for (double side : {1.0, 2.5, 40.0}) {
    const std::string path = output("per-face-cube-" + std::to_string(int(side * 10)) + ".vtk");
    spit(path, perFaceCubeVtk(side));
    const TriMesh cube = readTriMesh(path);
    const TriMeshSummary s = summarize(cube);
    std::cout << "per-face cube, side " << side << ": " << s.vertices << " vertices, " << s.components
              << " component(s), " << s.boundaryEdges << " boundary edges, volume "
              << (s.volume ? *s.volume : 0.0) << "\n";
    EXPECT_EQ(s.vertices, 8);
    EXPECT_EQ(s.triangles, 12);
    EXPECT_EQ(s.components, 1);
    ASSERT_TRUE(s.closed);
    EXPECT_NEAR(*s.volume, side * side * side, 1e-9 * side * side * side);
    // Each face keeps its own uv; the per-face normals cannot belong to a shared corner and are dropped.
    ASSERT_EQ(cube.FUV.rows(), 12);
    EXPECT_EQ(cube.UV.rows(), 24);
    EXPECT_FALSE(cube.vertexAttributes.has("Normals"));
  }
}

TEST(SurfaceFiles, MeshesWithoutDuplicatePointsAreReadUnchanged) {
  TriMesh pelvis = readTriMesh(kPelvis);
  pelvis.vertexAttributes.real["thickness"] = pelvis.V.col(2) * 3.5;
  const TriMesh meshes[] = {readTriMesh(kLiverSurface), pelvis, readTriMesh(kBody)};
  for (const TriMesh& mesh : meshes) {
    const TriMesh merged = mergeCoincidentVertices(mesh);
    EXPECT_EQ(merged.V, mesh.V);
    EXPECT_EQ(merged.F, mesh.F);
    EXPECT_EQ(merged.UV, mesh.UV);
    EXPECT_EQ(merged.FUV, mesh.FUV);
    expectSameAttributes(mesh.vertexAttributes, merged.vertexAttributes);
    expectSameAttributes(mesh.faceAttributes, merged.faceAttributes);
    // Through a VTK file, which keeps V as it is: same rows in the same order.
    const std::string path = output("unchanged-" + std::to_string(mesh.V.rows()) + ".vtp");
    writeTriMesh(path, mesh, options(true));
    const TriMesh read = readTriMesh(path);
    EXPECT_EQ(read.V, mesh.V);
    EXPECT_EQ(read.F, mesh.F);
  }
}

// Boxes of n x n quads per side with every triangle given its own corners: merging gives back the
// closed box, 6 n^2 + 2 vertices, whatever n; vertex values that agree at a corner are kept.
TEST(SurfaceFiles, ExplodedBoxesMergeToClosedSurfaces) {
  for (int n : {1, 2, 5}) {
    TriMesh exploded;
    std::vector<Eigen::RowVector3d> corners;
    for (int axis = 0; axis < 3; ++axis)
      for (int high = 0; high < 2; ++high)
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < n; ++j) {
            auto at = [&](int a, int b) {
              Eigen::RowVector3d p;
              p(axis) = high;
              p((axis + 1) % 3) = double(a) / n;
              p((axis + 2) % 3) = double(b) / n;
              return p;
            };
            const Eigen::RowVector3d q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            for (const auto& tri : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}})
              for (int c : (high ? tri : std::array<int, 3>{tri[0], tri[2], tri[1]})) corners.push_back(q[c]);
          }
    exploded.V.resize(Eigen::Index(corners.size()), 3);
    exploded.F.resize(exploded.V.rows() / 3, 3);
    for (Eigen::Index i = 0; i < exploded.V.rows(); ++i) exploded.V.row(i) = corners[std::size_t(i)];
    for (Eigen::Index f = 0; f < exploded.F.rows(); ++f) exploded.F.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
    exploded.vertexAttributes.real["height"] = exploded.V.col(2);  // agrees at every shared corner
    const TriMesh box = mergeCoincidentVertices(exploded);
    const TriMeshSummary s = summarize(box);
    std::cout << "exploded box n = " << n << ": " << exploded.V.rows() << " corners -> " << s.vertices
              << " vertices, volume " << (s.volume ? *s.volume : 0.0) << "\n";
    EXPECT_EQ(s.vertices, 6 * n * n + 2);
    EXPECT_EQ(s.components, 1);
    ASSERT_TRUE(s.closed);
    EXPECT_NEAR(*s.volume, 1.0, 1e-12);
    expectSameCorners(exploded, box, 0.0);
    EXPECT_EQ(box.vertexAttributes.real.at("height"), box.V.col(2));
  }
}

class SurfaceRoundTrip : public testing::TestWithParam<SurfaceFormat> {};

TEST_P(SurfaceRoundTrip, Liver) { expectSurfaceRoundTrip(readTriMesh(kLiverSurface), "liver", GetParam()); }

TEST_P(SurfaceRoundTrip, LiverWithPerVertexUv) {
  TriMesh liver = readTriMesh(kLiverSurface);
  liver.UV = liver.V.leftCols<2>() / 8.0;
  liver.FUV = liver.F;
  expectSurfaceRoundTrip(liver, "liver-uv", GetParam());
}

// Writing a binary STL whose coordinate float32 cannot hold names the output file, and leaves no file.
TEST(SurfaceFiles, BinaryStlBeyondFloat32IsRefusedNamingTheFile) {
  TriMesh liver = readTriMesh(kLiverSurface);
  liver.V(0, 2) = 1e60;
  const std::string path = output("beyond-float32.stl");
  try {
    writeTriMesh(path, liver, options(true));
    ADD_FAILURE() << "written";
  } catch (const BadInput& e) {
    std::cout << e.what() << "\n";
    EXPECT_EQ(std::string(e.what()).rfind(path + ": ", 0), 0u) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

// A closed surface keeps every vertex, and so its vertex numbers, where two vertices lie at one point (a
// transfer can land two skin vertices there); only STL, which stores no shared corners, merges them.
TEST_P(SurfaceRoundTrip, ClosedSurfaceWithTwoVerticesAtOnePoint) {
  TriMesh liver = readTriMesh(kLiverSurface);
  liver.V.row(liver.V.rows() - 1) = liver.V.row(0);
  expectSurfaceRoundTrip(liver, "liver-coincident", GetParam());
}

TEST_P(SurfaceRoundTrip, GluteusMedius) { expectSurfaceRoundTrip(readTriMesh(kGluteus), "gluteus", GetParam()); }

TEST_P(SurfaceRoundTrip, BodyWithUvSeamsAndGroups) {
  expectSurfaceRoundTrip(readTriMesh(kBody), "body", GetParam());
}

TEST_P(SurfaceRoundTrip, PelvisWithAttributes) {
  TriMesh pelvis = readTriMesh(kPelvis);
  pelvis.vertexAttributes.real["thickness"] = pelvis.V.col(2) * 3.5;
  pelvis.vertexAttributes.integer[kLabel] = Eigen::VectorXi::LinSpaced(pelvis.V.rows(), -3, 200);
  pelvis.faceAttributes.real["direction"] = Eigen::MatrixXd::Random(pelvis.F.rows(), 3);
  pelvis.faceAttributes.integer["group"] = Eigen::VectorXi::LinSpaced(pelvis.F.rows(), 0, 5);
  expectSurfaceRoundTrip(pelvis, "pelvis", GetParam());
}

INSTANTIATE_TEST_SUITE_P(Formats, SurfaceRoundTrip, testing::ValuesIn(kSurfaceFormats),
                         [](const testing::TestParamInfo<SurfaceFormat>& info) {
                           return std::string(info.param.ext + 1) + (info.param.binary ? "Binary" : "Ascii");
                         });

TEST(SurfaceFiles, WritersTagLps) {
  const TriMesh pelvis = readTriMesh(kPelvis);
  for (const char* name : {"tag.stl", "tag.obj", "tag.ply", "tag.vtk"}) {
    const std::string path = output(name);
    writeTriMesh(path, pelvis, options(true));
    EXPECT_NE(slurp(path).substr(0, 400).find("SPACE=LPS"), std::string::npos) << name;
  }
}

// A file the writer tagged LPS, re-tagged RAS by editing its text, reads back with x and y negated.
void expectRasTagFlips(const std::string& name, const std::string& lpsText, const std::string& rasText) {
  SCOPED_TRACE(name);
  const TriMesh pelvis = readTriMesh(kPelvis);
  const std::string path = output(name);
  writeTriMesh(path, pelvis, options(false));
  std::string text = slurp(path);
  const std::size_t at = text.find(lpsText);
  ASSERT_NE(at, std::string::npos);
  spit(path, text.replace(at, lpsText.size(), rasText));
  const TriMesh read = readTriMesh(path);
  EXPECT_TRUE(read.V.leftCols<2>().isApprox(-pelvis.V.leftCols<2>(), 1e-6));
  EXPECT_TRUE(read.V.col(2).isApprox(pelvis.V.col(2), 1e-6));
}

TEST(SurfaceFiles, RasTagsAreHonoured) {
  expectRasTagFlips("ras.vtk", "SPACE=LPS", "SPACE=RAS");
  expectRasTagFlips("ras.ply", "SPACE=LPS", "SPACE=RAS");
  expectRasTagFlips("ras.stl", "solid SPACE=LPS", "solid SPACE=RAS");
  expectRasTagFlips("ras.obj", "# SPACE=LPS", "# SPACE=RAS");
  expectRasTagFlips("ras.vtp", "76 80 83", "82 65 83");  // the field data string "LPS", as ASCII codes
}

// What a tet format keeps of the liver's tags: label (physical), region (elementary).
struct TetFormat {
  const char* ext;
  bool binary;
  bool label, region, vertexAttributes;
};

const TetFormat kTetFormats[] = {{".vtu", true, true, true, true},    {".vtu", false, true, true, true},
                                 {".vtk", true, true, true, true},    {".vtk", false, true, true, true},
                                 {".node", false, false, true, false}, {".mesh", false, true, false, false},
                                 {".msh", false, true, true, false}};

TEST(TetFiles, LiverGmshVersion1) {
  const TetMesh liver = readTetMesh(kLiverTets);
  EXPECT_EQ(liver.V.rows(), 181);
  EXPECT_EQ(liver.T.rows(), 596);
  EXPECT_EQ(liver.F.rows(), 0);
  const TetMeshSummary s = summarize(liver);
  EXPECT_EQ(s.inverted, 0);
  EXPECT_GT(s.minVolume, 0);
  EXPECT_NEAR(s.totalVolume, 36.5609, 0.0366);  // cubic units of the file, measured; 0.1 %
  EXPECT_EQ(s.tetsPerLabel, (std::map<int, long>{{1, 596}}));
  EXPECT_EQ(liver.tetAttributes.integer.at(kRegion), Eigen::VectorXi::Ones(596));
}

// Real Gmsh 4.1 files (testdata/gmsh, written by Gmsh; see SOURCE.md there).
TEST(TetFiles, Gmsh41CubeWithSubdomain) {
  const TetMesh cube = readTetMesh(kData + "/gmsh/cube_oriented_sub.msh");
  EXPECT_EQ(cube.V.rows(), 81);
  EXPECT_EQ(cube.T.rows(), 184);
  EXPECT_EQ(cube.F.rows(), 156);
  EXPECT_EQ(cube.tetAttributes.integer.at(kLabel), Eigen::VectorXi::Constant(184, 25));
  EXPECT_EQ(cube.tetAttributes.integer.at(kRegion), Eigen::VectorXi::Constant(184, 2));
  EXPECT_EQ(cube.faceAttributes.integer.at(kLabel), Eigen::VectorXi::Constant(156, 26));
  std::map<int, int> facesPerSurface;
  for (int region : cube.faceAttributes.integer.at(kRegion)) ++facesPerSurface[region];
  EXPECT_EQ(facesPerSurface, (std::map<int, int>{{7, 26}, {8, 26}, {9, 26}, {10, 26}, {11, 26}, {12, 26}}));
  // The tets fill the inner cube [0.1, 0.6]^3 and the triangles are its faces, 26 on each side.
  const TetMeshSummary s = summarize(cube);
  std::cout << "cube_oriented_sub.msh: tet volume " << s.totalVolume << ", " << s.inverted << " inverted\n";
  EXPECT_EQ(s.inverted, 0);
  EXPECT_NEAR(s.totalVolume, 0.125, 1e-12);
  EXPECT_NEAR(s.min.minCoeff(), 0.1, 1e-12);
  EXPECT_NEAR(s.max.maxCoeff(), 0.6, 1e-12);
  double area = 0;
  for (Eigen::Index f = 0; f < cube.F.rows(); ++f) {
    const Eigen::Vector3d a = cube.V.row(cube.F(f, 0)), b = cube.V.row(cube.F(f, 1)), c = cube.V.row(cube.F(f, 2));
    area += (b - a).cross(c - a).norm() / 2;
  }
  std::cout << "  triangle area " << area << "\n";
  EXPECT_NEAR(area, 6 * 0.25, 1e-12);

  // Ours, read back: the same mesh (written in 4.1, Gmsh's default).
  const std::string path = output("cube_oriented_sub.msh");
  writeTetMesh(path, cube, options(false));
  EXPECT_EQ(slurp(path).rfind("$MeshFormat\n4.1 0 8\n", 0), 0u);
  const TetMesh read = readTetMesh(path);
  EXPECT_EQ(read.V, cube.V);
  EXPECT_EQ(read.T, cube.T);
  EXPECT_EQ(read.F, cube.F);
  expectSameAttributes(cube.tetAttributes, read.tetAttributes);
  expectSameAttributes(cube.faceAttributes, read.faceAttributes);
}

TEST(TetFiles, Gmsh41TwoDimensionalWithLinesAndSparseTags) {
  const TetMesh mesh = readTetMesh(kData + "/gmsh/tagged_gmsh4.msh");
  EXPECT_EQ(mesh.V.rows(), 55);
  EXPECT_EQ(mesh.T.rows(), 0);
  EXPECT_EQ(mesh.F.rows(), 80);  // the 8 lines on curve 3 are skipped
  EXPECT_EQ(mesh.faceAttributes.integer.at(kLabel), Eigen::VectorXi::Constant(80, 8));
  EXPECT_EQ(mesh.faceAttributes.integer.at(kRegion), Eigen::VectorXi::Constant(80, 1));
  // Node tag 1 is the 4th node of the file, (0, -0.3, 0); element 34 (the first triangle) is 12 16 15.
  EXPECT_EQ(mesh.V.row(mesh.F(0, 0)), Eigen::RowVector3d(0.5, -0.3, 0));
  double area = 0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    area += (b - a).cross(c - a).z() / 2;  // signed: all triangles counter-clockwise
  }
  std::cout << "tagged_gmsh4.msh: signed area " << area << "\n";
  EXPECT_NEAR(area, 0.55, 1e-12);  // the polygon of SOURCE.md
}

class TetRoundTrip : public testing::TestWithParam<TetFormat> {};

TEST_P(TetRoundTrip, Liver) {
  const TetFormat& f = GetParam();
  TetMesh liver = readTetMesh(kLiverTets);
  liver.tetAttributes.integer[kLabel] = Eigen::VectorXi::LinSpaced(liver.T.rows(), 1, 9);
  liver.tetAttributes.integer[kRegion] = Eigen::VectorXi::LinSpaced(liver.T.rows(), 4, 2);
  if (f.vertexAttributes) liver.vertexAttributes.real["displacement"] = liver.V * 0.25;
  const std::string path = output(std::string("liver-") + (f.binary ? "binary" : "ascii") + f.ext);
  writeTetMesh(path, liver, options(f.binary));
  const TetMesh read = readTetMesh(path);
  EXPECT_EQ(read.V.rows(), liver.V.rows());
  EXPECT_LE((read.V - liver.V).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(read.T, liver.T);  // same order and orientation
  EXPECT_EQ(read.tetAttributes.has(kLabel), f.label);
  EXPECT_EQ(read.tetAttributes.has(kRegion), f.region);
  if (f.label) {
    EXPECT_EQ(read.tetAttributes.integer.at(kLabel), liver.tetAttributes.integer.at(kLabel));
  }
  if (f.region && std::string(f.ext) == ".msh") {
    // Gmsh 4.1 names an entity by its elementary tag and gives it one set of physical groups; these
    // regions span several labels, so each (region, label) pair becomes one entity numbered 1, 2, ...
    // The pairs must survive one to one.
    const Eigen::VectorXi &label = liver.tetAttributes.integer.at(kLabel), &region = liver.tetAttributes.integer.at(kRegion);
    const Eigen::VectorXi& readRegion = read.tetAttributes.integer.at(kRegion);
    std::map<std::pair<int, int>, std::set<int>> entities;
    std::set<int> tags;
    for (Eigen::Index t = 0; t < label.size(); ++t) {
      entities[{region(t), label(t)}].insert(readRegion(t));
      tags.insert(readRegion(t));
    }
    for (const auto& [pair, entity] : entities) EXPECT_EQ(entity.size(), 1u);
    EXPECT_EQ(tags.size(), entities.size());
  } else if (f.region) {
    EXPECT_EQ(read.tetAttributes.integer.at(kRegion), liver.tetAttributes.integer.at(kRegion));
  }
  if (f.vertexAttributes) expectSameAttributes(liver.vertexAttributes, read.vertexAttributes);
}

TEST_P(TetRoundTrip, LiverWithBoundaryTriangles) {
  const TetFormat& f = GetParam();
  TetMesh liver = readTetMesh(kLiverTets);
  liver.F = tetBoundary(liver.T);
  const std::string path = output(std::string("liver-faces-") + (f.binary ? "binary" : "ascii") + f.ext);
  writeTetMesh(path, liver, options(f.binary));
  const TetMesh read = readTetMesh(path);
  const bool keepsFaces = std::string(f.ext) != ".vtu" && std::string(f.ext) != ".vtk";
  EXPECT_EQ(read.F, keepsFaces ? liver.F : MatrixX3i(0, 3));
  EXPECT_EQ(read.T, liver.T);
}

INSTANTIATE_TEST_SUITE_P(Formats, TetRoundTrip, testing::ValuesIn(kTetFormats),
                         [](const testing::TestParamInfo<TetFormat>& info) {
                           return std::string(info.param.ext + 1) + (info.param.binary ? "Binary" : "Ascii");
                         });

TEST(TetFiles, InvertedTetsAreReorientedOnRead) {
  TetMesh liver = readTetMesh(kLiverTets);
  TetMesh inverted = liver;
  for (Eigen::Index t = 0; t < inverted.T.rows(); t += 3) std::swap(inverted.T(t, 0), inverted.T(t, 1));
  for (const char* ext : {".vtu", ".mesh", ".msh", ".node"}) {
    const std::string path = output(std::string("inverted") + ext);
    writeTetMesh(path, inverted, options(true));
    const TetMesh read = readTetMesh(path);
    EXPECT_EQ(summarize(read).inverted, 0) << ext;
    EXPECT_NEAR(tetVolumes(read.V, read.T).sum(), tetVolumes(liver.V, liver.T).sum(), 1e-9) << ext;
  }
}

}  // namespace
}  // namespace vesalius::io
