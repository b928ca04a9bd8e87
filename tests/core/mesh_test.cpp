// Meshes: tet volumes, outward boundaries of split cubes, validation, attributes.
#include "vesalius/core/attributes.h"
#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/mesh_measures.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

namespace vesalius {
namespace {

// Corners of the cube [0, s]^3, corner c at (bit 0, bit 1, bit 2) of c.
MatrixX3d cubeCorners(double s) {
  MatrixX3d V(8, 3);
  for (int c = 0; c < 8; ++c) V.row(c) << s * (c & 1), s * ((c >> 1) & 1), s * ((c >> 2) & 1);
  return V;
}

// Swaps two corners of every negatively oriented tet, so the split cubes below need no hand orientation.
MatrixX4i oriented(const MatrixX3d& V, MatrixX4i T) {
  const Eigen::VectorXd vol = tetVolumes(V, T);
  for (int t = 0; t < T.rows(); ++t)
    if (vol[t] < 0) std::swap(T(t, 2), T(t, 3));
  return T;
}

MatrixX4i cubeInFive(const MatrixX3d& V) {
  MatrixX4i T(5, 4);
  T << 0, 1, 2, 4,  // four corner tets ...
      3, 1, 2, 7,   //
      5, 1, 4, 7,   //
      6, 2, 4, 7,   //
      1, 2, 4, 7;   // ... around the regular tet in the middle
  return oriented(V, T);
}

MatrixX4i cubeInSix(const MatrixX3d& V) {
  MatrixX4i T(6, 4);
  T << 0, 1, 3, 7, 0, 1, 5, 7, 0, 2, 3, 7, 0, 2, 6, 7, 0, 4, 5, 7, 0, 4, 6, 7;
  return oriented(V, T);
}

// Every directed edge of a closed, consistently oriented surface appears once, its reverse once.
void expectClosedAndConsistent(const MatrixX3i& F) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{F(f, k), F(f, (k + 1) % 3)}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
}

TEST(Mesh, TetVolumesAreSigned) {
  MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  MatrixX4i T(2, 4);
  T << 0, 1, 2, 3, 0, 2, 1, 3;
  const Eigen::VectorXd vol = tetVolumes(V, T);
  ASSERT_EQ(vol.size(), 2);
  EXPECT_NEAR(vol[0], 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(vol[1], -1.0 / 6.0, 1e-15);
}

TEST(Mesh, CubeInFiveTetsHasAnOutwardBoundary) {
  const MatrixX3d V = cubeCorners(2.0);
  const MatrixX4i T = cubeInFive(V);
  EXPECT_NEAR(tetVolumes(V, T).sum(), 8.0, 1e-12);
  EXPECT_NEAR(tetVolumes(V, T)[4], 8.0 / 3.0, 1e-12);
  const MatrixX3i F = tetBoundary(T);
  EXPECT_EQ(F.rows(), 12);
  expectClosedAndConsistent(F);
  EXPECT_NEAR(enclosedVolume(V, F), 8.0, 1e-12);
}

TEST(Mesh, CubeInSixTetsHasAnOutwardBoundary) {
  const MatrixX3d V = cubeCorners(2.0);
  const MatrixX4i T = cubeInSix(V);
  const Eigen::VectorXd vol = tetVolumes(V, T);
  for (int t = 0; t < 6; ++t) EXPECT_NEAR(vol[t], 8.0 / 6.0, 1e-12);
  const MatrixX3i F = tetBoundary(T);
  EXPECT_EQ(F.rows(), 12);
  expectClosedAndConsistent(F);
  EXPECT_NEAR(enclosedVolume(V, F), 8.0, 1e-12);
}

TEST(Mesh, BoundaryOfOneTetIsItsFourFaces) {
  MatrixX3d V(4, 3);
  V << 1, 1, 1, 3, 1, 1, 1, 4, 1, 1, 1, 5;
  MatrixX4i T(1, 4);
  T << 0, 1, 2, 3;
  const MatrixX3i F = tetBoundary(T);
  EXPECT_EQ(F.rows(), 4);
  expectClosedAndConsistent(F);
  EXPECT_NEAR(enclosedVolume(V, F), tetVolumes(V, T)[0], 1e-12);
  EXPECT_NEAR(enclosedVolume(V, F), 2.0 * 3.0 * 4.0 / 6.0, 1e-12);
}

TriMesh twoTriangles() {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 0, 2, 3;
  return m;
}

void expectBadInputNaming(const TriMesh& m, const std::string& source) {
  try {
    m.validate(source);
    ADD_FAILURE() << "validate accepted a broken mesh";
  } catch (const BadInput& e) {
    EXPECT_EQ(e.file(), source);
    EXPECT_NE(std::string(e.what()).find(source), std::string::npos) << e.what();
  }
}

TEST(Mesh, TriMeshValidateRejectsBrokenMeshes) {
  EXPECT_NO_THROW(twoTriangles().validate("liver.stl"));
  TriMesh m = twoTriangles();
  m.V(2, 1) = std::numeric_limits<double>::quiet_NaN();
  expectBadInputNaming(m, "liver.stl");
  m = twoTriangles();
  m.V(0, 0) = std::numeric_limits<double>::infinity();
  expectBadInputNaming(m, "liver.stl");
  m = twoTriangles();
  m.F(1, 2) = 4;
  expectBadInputNaming(m, "liver.stl");
  m = twoTriangles();
  m.F(0, 0) = -1;
  expectBadInputNaming(m, "liver.stl");
  m = twoTriangles();
  m.vertexAttributes.integer[kLabel] = Eigen::VectorXi::Zero(3);
  expectBadInputNaming(m, "liver.stl");
  m = twoTriangles();
  m.faceAttributes.real["thickness"] = Eigen::MatrixXd::Zero(2, 1);
  m.vertexAttributes.integer[kRegion] = Eigen::VectorXi::Zero(4);
  EXPECT_NO_THROW(m.validate("liver.stl"));
}

TEST(Mesh, TetMeshValidateRejectsBrokenMeshes) {
  TetMesh m;
  m.V = cubeCorners(1.0);
  m.T = cubeInSix(m.V);
  m.tetAttributes.integer[kLabel] = Eigen::VectorXi::Constant(6, 3);
  EXPECT_NO_THROW(m.validate("organ.vtu"));
  TetMesh bad = m;
  bad.T(5, 3) = 8;
  EXPECT_THROW(bad.validate("organ.vtu"), BadInput);
  bad = m;
  bad.V(7, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(bad.validate("organ.vtu"), BadInput);
  bad = m;
  bad.tetAttributes.integer[kLabel] = Eigen::VectorXi::Constant(5, 3);
  try {
    bad.validate("organ.vtu");
    ADD_FAILURE() << "validate accepted a short attribute";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("organ.vtu"), std::string::npos) << e.what();
  }
}

TEST(MeshAttributes, CheckRowsNamesTheOwner) {
  AttributeSet a;
  EXPECT_TRUE(a.empty());
  a.real["uv"] = Eigen::MatrixXd::Zero(5, 2);
  a.integer[kLabel] = Eigen::VectorXi::Zero(5);
  EXPECT_FALSE(a.empty());
  EXPECT_TRUE(a.has("uv"));
  EXPECT_TRUE(a.has(kLabel));
  EXPECT_FALSE(a.has("thickness"));
  EXPECT_NO_THROW(a.checkRows(5, "skin.vtk"));
  try {
    a.checkRows(6, "skin.vtk");
    ADD_FAILURE() << "checkRows accepted the wrong count";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("skin.vtk"), std::string::npos) << e.what();
  }
}

TEST(MeshAttributes, SelectRowsKeepsTheListedRowsInOrder) {
  AttributeSet a;
  a.real["uv"] = Eigen::MatrixXd(4, 2);
  a.real["uv"] << 0, 0.5, 1, 1.5, 2, 2.5, 3, 3.5;
  a.integer[kLabel] = Eigen::VectorXi(4);
  a.integer[kLabel] << 10, 11, 12, 13;
  Eigen::VectorXi keep(3);
  keep << 3, 0, 3;
  const AttributeSet s = a.selectRows(keep);
  ASSERT_EQ(s.real.at("uv").rows(), 3);
  ASSERT_EQ(s.real.at("uv").cols(), 2);
  EXPECT_EQ(s.real.at("uv").row(0), Eigen::RowVector2d(3, 3.5));
  EXPECT_EQ(s.real.at("uv").row(1), Eigen::RowVector2d(0, 0.5));
  EXPECT_EQ(s.real.at("uv").row(2), Eigen::RowVector2d(3, 3.5));
  EXPECT_EQ(s.integer.at(kLabel), Eigen::Vector3i(13, 10, 13));
}

}  // namespace
}  // namespace vesalius
