// Real meshes from testdata/ read, written in every format, and read again (mesh_io.h): same counts,
// same corner coordinates (orientation included), same uv and attributes where the format carries them.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <filesystem>
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

class SurfaceRoundTrip : public testing::TestWithParam<SurfaceFormat> {};

TEST_P(SurfaceRoundTrip, Liver) { expectSurfaceRoundTrip(readTriMesh(kLiverSurface), "liver", GetParam()); }

TEST_P(SurfaceRoundTrip, LiverWithPerVertexUv) {
  TriMesh liver = readTriMesh(kLiverSurface);
  liver.UV = liver.V.leftCols<2>() / 8.0;
  liver.FUV = liver.F;
  expectSurfaceRoundTrip(liver, "liver-uv", GetParam());
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
  if (f.region) {
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
