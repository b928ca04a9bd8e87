// Mesh summaries for `vesalius info` on meshes whose answers are known by construction (mesh_io.h).
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

namespace vesalius::io {
namespace {

// An axis-aligned box [0,a]x[0,b]x[0,c] as 12 outward triangles.
TriMesh box(double a, double b, double c) {
  TriMesh mesh;
  mesh.V.resize(8, 3);
  mesh.V << 0, 0, 0, a, 0, 0, a, b, 0, 0, b, 0, 0, 0, c, a, 0, c, a, b, c, 0, b, c;
  mesh.F.resize(12, 3);
  mesh.F << 0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7;
  return mesh;
}

TEST(TriMeshSummary, ClosedBox) {
  const TriMeshSummary s = summarize(box(2, 3, 4));
  EXPECT_EQ(s.vertices, 8);
  EXPECT_EQ(s.triangles, 12);
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.components, 1);
  EXPECT_TRUE(s.closed);
  ASSERT_TRUE(s.volume.has_value());
  EXPECT_NEAR(*s.volume, 24.0, 1e-12);
  EXPECT_EQ(s.max, Eigen::Vector3d(2, 3, 4));
  EXPECT_NE(describe(s).find("enclosed volume: 24 mm^3"), std::string::npos) << describe(s);
}

TEST(TriMeshSummary, InsideOutBoxHasNegativeVolume) {
  TriMesh mesh = box(1, 1, 1);
  mesh.F.col(1).swap(mesh.F.col(2));
  EXPECT_NEAR(*summarize(mesh).volume, -1.0, 1e-12);
}

TEST(TriMeshSummary, OpenBoxHasBoundaryAndNoVolume) {
  TriMesh mesh = box(1, 1, 1);
  mesh.F.conservativeResize(11, 3);
  const TriMeshSummary s = summarize(mesh);
  EXPECT_EQ(s.boundaryEdges, 3);
  EXPECT_FALSE(s.closed);
  EXPECT_FALSE(s.volume.has_value());
}

TEST(TriMeshSummary, TwoBoxesAndANonManifoldFin) {
  const TriMesh a = box(1, 1, 1);
  TriMesh mesh;
  mesh.V.resize(17, 3);
  mesh.V << a.V, (a.V.rowwise() + Eigen::RowVector3d(5, 0, 0)), Eigen::RowVector3d(0.5, -1, 0);
  mesh.F.resize(25, 3);
  mesh.F << a.F, (a.F.array() + 8).matrix(), Eigen::RowVector3i(0, 1, 16);  // fin on edge (0,1)
  const TriMeshSummary s = summarize(mesh);
  EXPECT_EQ(s.components, 2);
  EXPECT_EQ(s.nonManifoldEdges, 1);
  EXPECT_EQ(s.boundaryEdges, 2);
  EXPECT_FALSE(s.closed);
}

TEST(TetMeshSummary, VolumesInvertedAndLabels) {
  TetMesh mesh;
  mesh.V.resize(5, 3);
  mesh.V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, -2;
  mesh.T.resize(3, 4);
  mesh.T << 0, 1, 2, 3, 0, 2, 1, 4, 0, 1, 3, 2;  // the last one is inverted
  Eigen::VectorXi& labels = mesh.tetAttributes.integer[kLabel];
  labels.resize(3);
  labels << 4, 4, 9;
  const TetMeshSummary s = summarize(mesh);
  EXPECT_EQ(s.tets, 3);
  EXPECT_NEAR(s.totalVolume, 1.0 / 6 + 2.0 / 6 - 1.0 / 6, 1e-15);
  EXPECT_NEAR(s.minVolume, -1.0 / 6, 1e-15);
  EXPECT_NEAR(s.maxVolume, 2.0 / 6, 1e-15);
  EXPECT_EQ(s.inverted, 1);
  EXPECT_EQ(s.tetsPerLabel, (std::map<int, long>{{4, 2}, {9, 1}}));
  EXPECT_NEAR(s.volumePerLabel.at(4), 0.5, 1e-15);
  EXPECT_NEAR(s.volumePerLabel.at(9), -1.0 / 6, 1e-15);
  EXPECT_NE(describe(s).find("labels (tets, mm^3): 4 (2, 0.5) 9 (1, -0.166667)"), std::string::npos)
      << describe(s);
}

}  // namespace
}  // namespace vesalius::io
