// The text mesh parsers and formatters on small hand-written inputs (mesh_formats.h).
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"

#include <gtest/gtest.h>

#include <string>

namespace vesalius::io {
namespace {

// A positively oriented unit tet with its outward surface.
TetMesh unitTet() {
  TetMesh mesh;
  mesh.V.resize(4, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  mesh.T.resize(1, 4);
  mesh.T << 0, 1, 2, 3;
  mesh.F = tetBoundary(mesh.T);
  return mesh;
}

TriMesh tetSurface() {
  const TetMesh tet = unitTet();
  TriMesh mesh;
  mesh.V = tet.V;
  mesh.F = tet.F;
  return mesh;
}

// Same triangles with the same corner coordinates, in the same order (vertex numbering may differ).
void expectSameCorners(const TriMesh& a, const TriMesh& b, double tolerance = 0) {
  ASSERT_EQ(a.F.rows(), b.F.rows());
  for (Eigen::Index f = 0; f < a.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      EXPECT_LE((a.V.row(a.F(f, c)) - b.V.row(b.F(f, c))).norm(), tolerance) << "face " << f << " corner " << c;
}

const char* const kTwoTriangleStl =
    "solid two\n"
    " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
    " facet normal 0 0 1\n  outer loop\n   vertex 1 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
    "endsolid two\n";

TEST(StlFormat, AsciiMergesSharedCorners) {
  const TriMesh mesh = parseStl(kTwoTriangleStl, "two.stl");
  EXPECT_EQ(mesh.V.rows(), 4);
  EXPECT_EQ(mesh.F.rows(), 2);
  EXPECT_EQ(mesh.F(1, 0), mesh.F(0, 1));  // (1,0,0) is one vertex
  EXPECT_EQ(mesh.V.row(mesh.F(1, 1)), Eigen::RowVector3d(1, 1, 0));
}

TEST(StlFormat, AsciiSpaceRasIsFlipped) {
  std::string text = kTwoTriangleStl;
  text.replace(0, 9, "solid SPACE=RAS");
  const TriMesh mesh = parseStl(text, "ras.stl");
  EXPECT_EQ(mesh.V.row(mesh.F(1, 1)), Eigen::RowVector3d(-1, -1, 0));
}

TEST(StlFormat, BinaryRoundTripAndHeaderTag) {
  const TriMesh surface = tetSurface();
  const std::string bytes = formatStlBinary(surface);
  EXPECT_EQ(bytes.size(), 84u + 50u * 4u);
  EXPECT_EQ(bytes.substr(0, 9), "SPACE=LPS");
  const TriMesh read = parseStl(bytes, "tet.stl");
  EXPECT_EQ(read.V.rows(), 4);
  expectSameCorners(surface, read);
}

TEST(StlFormat, BinaryWhoseHeaderStartsWithSolid) {
  std::string bytes = formatStlBinary(tetSurface());
  bytes.replace(0, 12, "solid part 1");
  const TriMesh read = parseStl(bytes, "solid.stl");
  EXPECT_EQ(read.F.rows(), 4);
  expectSameCorners(tetSurface(), read);
}

TEST(StlFormat, BinaryRasHeaderIsFlipped) {
  std::string bytes = formatStlBinary(tetSurface());
  bytes.replace(0, 9, "SPACE=RAS");
  TriMesh flipped = tetSurface();
  flipped.V.leftCols<2>() *= -1;
  expectSameCorners(flipped, parseStl(bytes, "ras.stl"));
}

TEST(StlFormat, AsciiRoundTripIsExact) {
  TriMesh surface = tetSurface();
  surface.V(1, 0) = 0.1 + 1e-12;
  const std::string text = formatStlAscii(surface);
  EXPECT_EQ(text.rfind("solid SPACE=LPS", 0), 0u);
  expectSameCorners(surface, parseStl(text, "tet.stl"));
}

TEST(ObjFormat, CornerFormsNegativeIndicesAndPolygons) {
  const TriMesh mesh = parseObj(
      "# a unit square and a triangle\n"
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
      "vn 0 0 1\n"
      "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
      "f -4/-4 -2/-2 -1/-1\n",
      "square.obj");
  ASSERT_EQ(mesh.F.rows(), 3);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(mesh.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(mesh.F.row(2), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(mesh.FUV, mesh.F);
  EXPECT_EQ(mesh.UV.row(2), Eigen::RowVector2d(1, 1));
  EXPECT_TRUE(mesh.faceAttributes.empty());
}

TEST(ObjFormat, VertexNormalFormWithoutUv) {
  const TriMesh mesh = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n", "vn.obj");
  EXPECT_EQ(mesh.F.rows(), 1);
  EXPECT_EQ(mesh.FUV.rows(), 0);
  EXPECT_EQ(mesh.UV.rows(), 0);
}

TEST(ObjFormat, GroupsBecomeFaceAttribute) {
  const std::string vertices = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const TriMesh named =
      parseObj(vertices + "f 1 2 3\ng arm\nf 1 2 4\ng leg\nf 1 3 4\ng arm\nf 2 3 4\n", "named.obj");
  EXPECT_EQ(named.faceAttributes.integer.at("group"), Eigen::Vector4i(0, 1, 2, 1));
  const TriMesh numbered = parseObj(vertices + "g 7\nf 1 2 3\ng 3\nf 1 2 4\n", "numbered.obj");
  EXPECT_EQ(numbered.faceAttributes.integer.at("group"), Eigen::Vector2i(7, 3));
  const TriMesh single = parseObj(vertices + "g body\nf 1 2 3\n", "single.obj");
  EXPECT_FALSE(single.faceAttributes.has("group"));
}

TEST(ObjFormat, SpaceRasTagFlipsXAndYOnly) {
  const std::string body = "v 1 2 3\nv 4 5 6\nv 7 8 10\nvt 0.5 0.25\nf 1/1 2/1 3/1\n";
  const TriMesh ras = parseObj("# SPACE=RAS\n" + body, "ras.obj");
  EXPECT_EQ(ras.V.row(0), Eigen::RowVector3d(-1, -2, 3));
  EXPECT_EQ(ras.V.row(2), Eigen::RowVector3d(-7, -8, 10));
  EXPECT_EQ(ras.UV.row(0), Eigen::RowVector2d(0.5, 0.25));
  const TriMesh lps = parseObj("# SPACE=LPS\n" + body, "lps.obj");
  EXPECT_EQ(lps.V.row(0), Eigen::RowVector3d(1, 2, 3));
  const TriMesh untagged = parseObj(body, "plain.obj");
  EXPECT_EQ(untagged.V.row(0), Eigen::RowVector3d(1, 2, 3));
}

TEST(ObjFormat, RoundTripKeepsUvAndGroups) {
  TriMesh mesh = tetSurface();
  mesh.V(2, 2) = 1.0 / 3.0;
  mesh.UV.resize(3, 2);
  mesh.UV << 0, 0, 1, 0, 0.125, 1.0 / 7.0;
  mesh.FUV.resize(4, 3);
  mesh.FUV << 0, 1, 2, 2, 1, 0, 0, 2, 1, 1, 1, 1;
  mesh.faceAttributes.integer["group"] = Eigen::Vector4i(5, 5, 9, 2);
  const std::string text = formatObj(mesh);
  EXPECT_NE(text.find("# SPACE=LPS\n"), std::string::npos);
  const TriMesh read = parseObj(text, "round.obj");
  EXPECT_EQ(read.V, mesh.V);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(read.UV, mesh.UV);
  EXPECT_EQ(read.FUV, mesh.FUV);
  EXPECT_EQ(read.faceAttributes.integer.at("group"), mesh.faceAttributes.integer.at("group"));
}

TEST(TetGenFormat, ZeroBasedWithRegionsMarkersAndInvertedTet) {
  const std::string node =
      "# nodes\n5 3 1 1\n0 0 0 0 0.5 1\n1 1 0 0 1.5 1\n2 0 1 0 2.5 0\n3 0 0 1 3.5 0\n4 1 1 1 4.5 2\n";
  const std::string ele = "2 4 1\n0 0 1 2 3 7\n1 1 3 2 4 8  # the second tet is inverted\n";
  const std::string face = "1 1\n0 0 2 1 -1\n";
  const TetMesh mesh = parseTetGen(node, ele, face, "small");
  EXPECT_EQ(mesh.V.rows(), 5);
  EXPECT_EQ(mesh.T.row(0), Eigen::RowVector4i(0, 1, 2, 3));
  EXPECT_EQ(mesh.T.row(1), Eigen::RowVector4i(1, 3, 4, 2));
  EXPECT_GT(tetVolumes(mesh.V, mesh.T).minCoeff(), 0);
  EXPECT_EQ(mesh.tetAttributes.integer.at(kRegion), Eigen::Vector2i(7, 8));
  EXPECT_EQ(mesh.vertexAttributes.real.at("attribute")(4, 0), 4.5);
  EXPECT_EQ(mesh.vertexAttributes.integer.at("marker")(4), 2);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.faceAttributes.integer.at("marker")(0), -1);
}

TEST(TetGenFormat, OneBasedRoundTrip) {
  TetMesh mesh = unitTet();
  mesh.tetAttributes.integer[kRegion] = Eigen::VectorXi::Constant(1, 3);
  mesh.faceAttributes.integer["marker"] = Eigen::Vector4i(1, 2, 3, 4);
  const TetGenFiles files = formatTetGen(mesh);
  EXPECT_EQ(files.node.rfind("# ", 0), 0u);
  EXPECT_NE(files.node.find("SPACE=LPS"), std::string::npos);
  const TetMesh read = parseTetGen(files.node, files.ele, files.face, "tet");
  EXPECT_EQ(read.V, mesh.V);
  EXPECT_EQ(read.T, mesh.T);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(read.tetAttributes.integer.at(kRegion), mesh.tetAttributes.integer.at(kRegion));
  EXPECT_EQ(read.faceAttributes.integer.at("marker"), mesh.faceAttributes.integer.at("marker"));
}

TEST(MeditFormat, SectionsRefsAndSkippedSections) {
  const TetMesh mesh = parseMedit(
      "MeshVersionFormatted 2\n# SPACE=RAS\nDimension\n3\n"
      "Vertices\n4\n0 0 0 1\n1 0 0 1\n0 1 0 2\n0 0 1 2\n"
      "Edges\n1\n1 2 0\nCorners 2 1 2\n"
      "Triangles\n1\n1 3 2 5\n"
      "Tetrahedra\n1\n1 2 4 3 9\nEnd\n",
      "small.mesh");
  EXPECT_EQ(mesh.V.row(1), Eigen::RowVector3d(-1, 0, 0));
  EXPECT_GT(tetVolumes(mesh.V, mesh.T)(0), 0);
  EXPECT_EQ(mesh.vertexAttributes.integer.at(kLabel), Eigen::Vector4i(1, 1, 2, 2));
  EXPECT_EQ(mesh.tetAttributes.integer.at(kLabel)(0), 9);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.faceAttributes.integer.at(kLabel)(0), 5);
}

TEST(MeditFormat, RoundTripDropsAllZeroRefs) {
  TetMesh mesh = unitTet();
  mesh.tetAttributes.integer[kLabel] = Eigen::VectorXi::Constant(1, 4);
  const TetMesh read = parseMedit(formatMedit(mesh), "tet.mesh");
  EXPECT_EQ(read.V, mesh.V);
  EXPECT_EQ(read.T, mesh.T);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(read.tetAttributes.integer.at(kLabel)(0), 4);
  EXPECT_TRUE(read.vertexAttributes.empty());
  EXPECT_TRUE(read.faceAttributes.empty());
}

TEST(GmshFormat, Version1WithSparseNodeNumbers) {
  const TetMesh mesh = parseGmsh(
      "$NOD\n4\n10 0 0 0\n20 1 0 0\n30 0 1 0\n40 0 0 1\n$ENDNOD\n"
      "$ELM\n3\n1 15 0 0 1 10\n2 2 3 1 3 10 30 20\n3 4 2 6 4 10 20 40 30\n$ENDELM\n",
      "v1.msh");
  EXPECT_EQ(mesh.T.row(0), Eigen::RowVector4i(0, 1, 2, 3));  // reoriented
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.tetAttributes.integer.at(kLabel)(0), 2);
  EXPECT_EQ(mesh.tetAttributes.integer.at(kRegion)(0), 6);
  EXPECT_EQ(mesh.faceAttributes.integer.at(kLabel)(0), 3);
}

TEST(GmshFormat, Version2SkipsUnknownSectionsAndLines) {
  const TetMesh mesh = parseGmsh(
      "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"liver\"\n$EndPhysicalNames\n"
      "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
      "$Elements\n2\n1 1 2 0 1 1 2\n2 4 3 1 1 0 1 2 3 4\n$EndElements\n",
      "v2.msh");
  EXPECT_EQ(mesh.T.rows(), 1);
  EXPECT_EQ(mesh.F.rows(), 0);
  EXPECT_EQ(mesh.tetAttributes.integer.at(kLabel)(0), 1);
  EXPECT_EQ(mesh.tetAttributes.integer.at(kRegion)(0), 1);
}

TEST(GmshFormat, Version2RoundTrip) {
  TetMesh mesh = unitTet();
  mesh.V(3, 2) = 1.0 / 3.0;
  mesh.tetAttributes.integer[kLabel] = Eigen::VectorXi::Constant(1, 12);
  const TetMesh read = parseGmsh(formatGmsh(mesh), "tet.msh");
  EXPECT_EQ(read.V, mesh.V);
  EXPECT_EQ(read.T, mesh.T);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(read.tetAttributes.integer.at(kLabel)(0), 12);
  EXPECT_FALSE(read.tetAttributes.has(kRegion));
}

TEST(GmshFormat, RejectsVersion4AndBinary) {
  try {
    parseGmsh("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", "new.msh");
    FAIL() << "version 4 accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("version 2 ASCII"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseGmsh("$MeshFormat\n2.2 1 8\n$EndMeshFormat\n", "binary.msh"), BadInput);
}

}  // namespace
}  // namespace vesalius::io
