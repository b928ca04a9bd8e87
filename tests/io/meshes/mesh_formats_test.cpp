// The text mesh parsers and formatters on small hand-written inputs (mesh_formats.h).
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"

#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <string>
#include <utility>

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

// Binary STL stores float32: a coordinate beyond its range (fuzz_stl read 2e113 from an ASCII file) is
// refused naming the destination rather than written as infinity, on every axis and sign; the largest
// float32 magnitudes are written and read back.
TEST(StlFormat, BinaryRefusesCoordinatesBeyondFloat32) {
  const double largest = double(std::numeric_limits<float>::max());
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {1.0, -1.0}) {
      TriMesh surface = tetSurface();
      surface.V(3, axis) = sign * 2e113;
      try {
        formatStlBinary(surface, "out.stl");
        ADD_FAILURE() << "axis " << axis << " sign " << sign << " was written";
      } catch (const BadInput& e) {
        EXPECT_EQ(std::string(e.what()).rfind("out.stl: vertex 3 has a coordinate beyond the float32 range", 0), 0u)
            << e.what();
      }
      surface.V(3, axis) = sign * largest;
      const TriMesh back = parseStl(formatStlBinary(surface, "out.stl"), "out.stl");
      std::cout << "axis " << axis << ": " << sign * largest << " mm reads back as " << back.V.cwiseAbs().maxCoeff()
                << "\n";
      expectSameCorners(surface, back);
    }
  TriMesh surface = tetSurface();
  surface.V(0, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(formatStlBinary(surface, "out.stl"), BadInput);
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
  const std::string text = formatGmsh(mesh, GmshVersion::k22);
  ASSERT_EQ(text.rfind("$MeshFormat\n2.2 0 8\n", 0), 0u);
  const TetMesh read = parseGmsh(text, "tet.msh");
  EXPECT_EQ(read.V, mesh.V);
  EXPECT_EQ(read.T, mesh.T);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(read.tetAttributes.integer.at(kLabel)(0), 12);
  EXPECT_FALSE(read.tetAttributes.has(kRegion));
}

// An n x n x n grid of unit cubes, each cut into 6 positively oriented tets, with its boundary; tets
// labelled by the octant-like slab they are in, boundary triangles by their face direction.
TetMesh tetGrid(int n) {
  TetMesh mesh;
  const int side = n + 1;
  mesh.V.resize(side * side * side, 3);
  for (int z = 0; z < side; ++z)
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) mesh.V.row((z * side + y) * side + x) << x * 1.5, y * 0.5, z / 3.0;
  static const int kCube[6][4] = {{0, 1, 3, 7}, {0, 3, 2, 7}, {0, 2, 6, 7}, {0, 6, 4, 7}, {0, 4, 5, 7}, {0, 5, 1, 7}};
  mesh.T.resize(6 * n * n * n, 4);
  Eigen::Index t = 0;
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        for (const auto& tet : kCube) {
          for (int c = 0; c < 4; ++c) {
            const int corner = tet[c];
            mesh.T(t, c) = ((z + (corner >> 2 & 1)) * side + y + (corner >> 1 & 1)) * side + x + (corner & 1);
          }
          ++t;
        }
  orientTetsPositively(mesh.V, mesh.T);
  mesh.F = tetBoundary(mesh.T);
  mesh.tetAttributes.integer[kLabel] = Eigen::VectorXi(mesh.T.rows());
  for (Eigen::Index i = 0; i < mesh.T.rows(); ++i) mesh.tetAttributes.integer[kLabel](i) = 1 + int(i * 3 / mesh.T.rows());
  mesh.faceAttributes.integer[kLabel] = Eigen::VectorXi(mesh.F.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) mesh.faceAttributes.integer[kLabel](f) = 10 + int(f % 4);
  return mesh;
}

void expectSameMesh(const TetMesh& read, const TetMesh& mesh) {
  EXPECT_EQ(read.V, mesh.V);
  EXPECT_EQ(read.T, mesh.T);
  EXPECT_EQ(read.F, mesh.F);
  EXPECT_EQ(read.tetAttributes.integer.at(kLabel), mesh.tetAttributes.integer.at(kLabel));
  EXPECT_EQ(read.faceAttributes.integer.at(kLabel), mesh.faceAttributes.integer.at(kLabel));
}

TEST(GmshFormat, Version41RoundTripKeepsOrderAndTags) {
  for (int n : {1, 2, 4}) {
    TetMesh mesh = tetGrid(n);
    mesh.V(0, 0) = 1.0 / 3.0;  // a coordinate that needs all 17 digits
    const std::string text = formatGmsh(mesh);
    ASSERT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n", 0), 0u);
    const TetMesh read = parseGmsh(text, "grid.msh");
    std::cout << "grid " << n << ": " << mesh.V.rows() << " nodes, " << mesh.T.rows() << " tets, " << mesh.F.rows()
              << " triangles, " << text.size() << " bytes\n";
    expectSameMesh(read, mesh);
    // Without elementary tags every entity is named by its physical tag.
    EXPECT_EQ(read.tetAttributes.integer.at(kRegion), mesh.tetAttributes.integer.at(kLabel));
    EXPECT_EQ(read.faceAttributes.integer.at(kRegion), mesh.faceAttributes.integer.at(kLabel));

    // Elementary tags that name entities (one physical group each) come back as they were.
    TetMesh withRegions = mesh;
    withRegions.tetAttributes.integer[kRegion] = 100 + withRegions.tetAttributes.integer[kLabel].array();
    withRegions.faceAttributes.integer[kRegion] = 7 * withRegions.faceAttributes.integer[kLabel];
    const TetMesh readRegions = parseGmsh(formatGmsh(withRegions), "grid.msh");
    expectSameMesh(readRegions, withRegions);
    EXPECT_EQ(readRegions.tetAttributes.integer.at(kRegion), withRegions.tetAttributes.integer.at(kRegion));
    EXPECT_EQ(readRegions.faceAttributes.integer.at(kRegion), withRegions.faceAttributes.integer.at(kRegion));

    // And both versions agree on everything the mesh holds.
    const TetMesh viaVersion2 = parseGmsh(formatGmsh(withRegions, GmshVersion::k22), "grid2.msh");
    expectSameMesh(viaVersion2, readRegions);
  }
}

TEST(GmshFormat, Version41UnlabelledAndEmptyMeshes) {
  TetMesh bare = unitTet();  // no attributes at all
  const TetMesh read = parseGmsh(formatGmsh(bare), "bare.msh");
  EXPECT_EQ(read.V, bare.V);
  EXPECT_EQ(read.T, bare.T);
  EXPECT_EQ(read.F, bare.F);
  EXPECT_FALSE(read.tetAttributes.has(kLabel));
  EXPECT_FALSE(read.faceAttributes.has(kLabel));

  TetMesh pointsOnly;
  pointsOnly.V = bare.V;
  const TetMesh readPoints = parseGmsh(formatGmsh(pointsOnly), "points.msh");
  EXPECT_EQ(readPoints.V, pointsOnly.V);
  EXPECT_EQ(readPoints.T.rows(), 0);

  const TetMesh empty = parseGmsh(formatGmsh(TetMesh()), "empty.msh");
  EXPECT_EQ(empty.V.rows(), 0);
  EXPECT_EQ(empty.T.rows(), 0);
}

// The example of the manual's 4.1 section, reduced to its mesh: parametric nodes, a point element and
// a line skipped, an entity with two physical groups (the first counts), tags not in file order.
TEST(GmshFormat, Version41ByHand) {
  const TetMesh mesh = parseGmsh(
      "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
      "$Entities\n1 1 1 1\n"
      "1 0 0 0 0\n"
      "1 0 0 0 1 0 0 0 0\n"
      "5 0 0 0 1 1 0 2 7 3 0\n"
      "2 0 0 0 1 1 1 1 9 0\n$EndEntities\n"
      "$Nodes\n3 4 1 40\n"
      "0 1 0 1\n40\n0 0 0\n"
      "2 5 1 2\n10\n20\n1 0 0 0.5 0.5\n0 1 0 0.1 0.2\n"
      "3 2 0 1\n30\n0 0 1\n$EndNodes\n"
      "$Elements\n4 4 1 9\n"
      "0 1 15 1\n9 40\n"
      "1 1 1 1\n8 40 10\n"
      "3 2 4 1\n2 40 20 10 30\n"
      "2 5 2 1\n1 40 20 10\n$EndElements\n",
      "hand.msh");
  ASSERT_EQ(mesh.V.rows(), 4);
  EXPECT_EQ(mesh.V.row(0), Eigen::RowVector3d(0, 0, 0));  // node 40
  EXPECT_EQ(mesh.V.row(2), Eigen::RowVector3d(0, 1, 0));  // node 20, parametric u v skipped
  ASSERT_EQ(mesh.T.rows(), 1);
  EXPECT_GT(tetVolumes(mesh.V, mesh.T)(0), 0);  // reoriented
  EXPECT_EQ(mesh.tetAttributes.integer.at(kLabel)(0), 9);
  EXPECT_EQ(mesh.tetAttributes.integer.at(kRegion)(0), 2);
  ASSERT_EQ(mesh.F.rows(), 1);
  EXPECT_EQ(mesh.F.row(0), Eigen::RowVector3i(0, 2, 1));
  EXPECT_EQ(mesh.faceAttributes.integer.at(kLabel)(0), 7);
  EXPECT_EQ(mesh.faceAttributes.integer.at(kRegion)(0), 5);
}

TEST(GmshFormat, RejectsVersion40AndBinary) {
  const std::pair<const char*, const char*> cases[] = {
      {"$MeshFormat\n4 0 8\n$EndMeshFormat\n", "line 2: Gmsh format 4 is not supported (save as version 4.1"},
      {"$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", "line 2: Gmsh format 3.0 is not supported"},
      {"$MeshFormat\n4.1 1 8\n$EndMeshFormat\n", "line 2: binary Gmsh files are not supported"},
      {"$MeshFormat\n2.2 1 8\n$EndMeshFormat\n", "line 2: binary Gmsh files are not supported"}};
  for (const auto& [text, expected] : cases) {
    try {
      parseGmsh(text, "new.msh");
      ADD_FAILURE() << "accepted " << text;
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("new.msh: ") + expected), std::string::npos) << e.what();
    }
  }
}

// Every cut of a valid 4.1 file at a line break, and files whose counts or references lie, must give a
// BadInput naming the file; none may crash or allocate what the header claims.
TEST(GmshFormat, Version41HostileInput) {
  const std::string good = formatGmsh(tetGrid(1));
  int cuts = 0;
  for (std::size_t end = good.find('\n'); end + 1 < good.size(); end = good.find('\n', end + 1)) {
    const std::string cut = good.substr(0, end + 1);
    if (cut.size() < 40) continue;  // the $MeshFormat section alone: a valid file without nodes
    ++cuts;
    try {
      parseGmsh(cut, "cut.msh");
      ADD_FAILURE() << "accepted a cut after " << cut.size() << " bytes";
    } catch (const BadInput& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.msh", 0), 0u) << e.what();
    }
  }
  std::cout << cuts << " cuts refused\n";
  EXPECT_GT(cuts, 50);

  const std::string head = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  const std::string entities = "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n$EndEntities\n";
  const std::string nodes = "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n";
  const std::pair<std::string, const char*> cases[] = {
      {head + "$Nodes\n1 99999999999 1 4\n", "line 5: bad node count 99999999999 for a file of"},
      {head + "$Nodes\n1 4 1 4\n3 1 0 4000000\n", "line 6: bad node count of the block 4000000"},
      {head + "$Nodes\n1 4 1 4\n3 1 0 5\n", "node blocks hold more than the 4 nodes of the header"},
      {head + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n$EndNodes\n", "line 13: section ends early"},
      {head + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n2\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n",
       "node tag 2 used twice"},
      {head + "$Nodes\n1 4 1 4\n3 1 2 4\n", "line 6: parametric flag 2"},
      {head + "$Nodes\n1 4 1 4\n7 1 0 4\n", "line 6: entity dimension 7"},
      {head + "$Nodes\n1 4 1 4\n3 1 0 3\n1\n2\n3\n0 0 0\n1 0 0\n0 1 0\n$EndNodes\n",
       "node blocks hold 3 nodes, the header says 4"},
      {head + "$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 nan\n$EndNodes\n",
       "line 14: bad node coordinate 'nan'"},
      {head + nodes + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 9\n$EndElements\n", "node 9 is not in the node section"},
      {head + nodes + "$Elements\n1 1 1 1\n3 1 5 1\n1 1 2 3 4 1 2 3 4\n$EndElements\n",
       "element type 5 (hexahedron) is not supported"},
      {head + nodes + "$Elements\n1 1 1 1\n3 1 2 1\n1 1 2 3\n$EndElements\n", "triangles on an entity of dimension 3"},
      {head + nodes + "$Elements\n1 2 1 2\n3 1 4 1\n1 1 2 3 4\n$EndElements\n",
       "element blocks hold 1 elements, the header says 2"},
      {head + nodes + "$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 4 5\n$EndElements\n", "unexpected '5'"},
      {head + entities + nodes + "$Elements\n1 1 1 1\n3 2 4 1\n1 1 2 3 4\n$EndElements\n",
       "entity 2 of dimension 3, which $Entities does not list"},
      {head + "$Entities\n0 0 0 99999999\n", "line 5: bad entity count 99999999"},
      {head + "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 5000000 1\n", "bad physical tag count 5000000"},
      {head + "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 0 0\n1 0 0 0 1 1 1 0 0\n", "line 7: expected $EndEntities"},
      {head + "$Entities\n0 0 0 2\n1 0 0 0 1 1 1 0 0\n$EndEntities\n", "line 7: section ends early, in entity tag"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      parseGmsh(text, "hostile.msh");
      ADD_FAILURE() << "accepted:\n" << text;
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("hostile.msh", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace vesalius::io
