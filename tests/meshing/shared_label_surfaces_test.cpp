// Shared surfaces of touching labels (SurfaceNets, Frisken 2022): every label's surface is a closed
// 2-manifold free of crossings, touching labels use the very same triangles, volumes match the voxels,
// and diagonal contacts are repaired. On the test CT's TotalSegmentator map, all 59 labels at once.
#include "vesalius/meshing/shared_label_surfaces.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "test_label_maps.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

namespace vesalius::meshing {
namespace {

// A ball of radius 12 mm cut by the plane x = 0 into labels 1 (x < 0) and 2, with a ball of label 3
// (radius 5 mm) sunk into label 2's side, on a grid tilted about z and flipped along j.
LabelMap splitBall() {
  GridGeometry g;
  g.size = Eigen::Vector3i(40, 40, 36);
  g.spacing = Eigen::Vector3d(0.8, 0.8, 1.0);
  g.direction = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                Eigen::Vector3d(1, -1, 1).asDiagonal();
  g.origin = -g.direction * g.spacing.cwiseProduct(Eigen::Vector3d(20, 20, 18));
  return test::paintedLabelMap(g, [](const Eigen::Vector3d& p) {
    if ((p - Eigen::Vector3d(9, 0, 0)).norm() <= 5.0) return 3;
    return p.norm() <= 12.0 ? (p.x() < 0 ? 1 : 2) : 0;
  });
}

double voxelVolume(const LabelMap& map, Label id) {
  long count = 0;
  for (Label l : map.labels.values) count += l == id;
  return double(count) * map.labels.geometry.spacing.prod();
}

void expectClosedAndClean(const TriMesh& mesh, const std::string& name) {
  SCOPED_TRACE(name);
  const EdgeCounts edges = countEdges(mesh.F);
  EXPECT_EQ(edges.boundary, 0);
  EXPECT_EQ(edges.nonManifold, 0);
  EXPECT_EQ(triangleComponents(mesh.V.rows(), mesh.F), 1);
  EXPECT_TRUE(selfIntersections(mesh.V, mesh.F).empty());
}

TEST(SharedLabelSurfaces, TouchingLabelsShareTheirTrianglesAndKeepTheirVolumes) {
  const LabelMap map = splitBall();
  const SharedLabelSurfaces s = sharedLabelSurfaces(map, {});
  ASSERT_EQ(s.ids, (std::vector<Label>{1, 2, 3}));
  EXPECT_TRUE(selfIntersections(s.V, s.F).empty());
  std::map<Label, double> volume;
  for (Label id : s.ids) {
    const TriMesh mesh = surfaceOfLabel(s, id);
    expectClosedAndClean(mesh, "label " + std::to_string(id));
    volume[id] = enclosedVolume(mesh.V, mesh.F);
    EXPECT_NEAR(volume[id] / voxelVolume(map, id), 1.0, 0.002) << id;
  }
  // Shared triangles: the labels' volumes add up to what the faces on the outside enclose, to round-off.
  TriMesh outside;
  outside.V = s.V;
  outside.F.resize(s.F.rows(), 3);
  Eigen::Index count = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (s.sides(f, 1) == 0) outside.F.row(count++) = s.F.row(f);
    else if (s.sides(f, 0) == 0) outside.F.row(count++) << s.F(f, 0), s.F(f, 2), s.F(f, 1);
  outside.F.conservativeResize(count, 3);
  EXPECT_NEAR(volume[1] + volume[2] + volume[3], enclosedVolume(outside.V, outside.F), 1e-9 * volume[2]);
  // The cut plane x = 0 stays flat: interface vertices of labels 1 and 2 lie within half a voxel of it.
  double worst = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (s.sides(f, 0) + s.sides(f, 1) == 3 && s.sides(f, 0) * s.sides(f, 1) == 2)
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(s.V(s.F(f, k), 0)));
  EXPECT_GT(worst, 0.0);
  EXPECT_LT(worst, 0.5);
}

// Where labels 1 and 2 touch: the disc x = 0 of the 12 mm ball, facing out of label 1 (+x) as seen from it
// and reversed as seen from label 2; labels 1 and 3 do not touch.
TEST(SharedLabelSurfaces, InterfaceOfTwoLabelsIsWhereTheyTouch) {
  const SharedLabelSurfaces s = sharedLabelSurfaces(splitBall(), {});
  const TriMesh disc = interfaceOfLabels(s, 1, 2);
  ASSERT_GT(disc.F.rows(), 0);
  EXPECT_EQ(triangleComponents(disc.V.rows(), disc.F), 1);
  EXPECT_EQ(countEdges(disc.F).nonManifold, 0);
  EXPECT_GT(countEdges(disc.F).boundary, 0);
  EXPECT_LT(disc.V.col(0).cwiseAbs().maxCoeff(), 0.5);
  const double area = triangleAreas(disc.V, disc.F).sum();
  EXPECT_NEAR(area / (M_PI * 12.0 * 12.0), 1.0, 0.05) << area;  // measured 0.988
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // area-weighted, 2 × area × mean unit normal
  for (Eigen::Index f = 0; f < disc.F.rows(); ++f)
    normal += (disc.V.row(disc.F(f, 1)) - disc.V.row(disc.F(f, 0)))
                  .cross(disc.V.row(disc.F(f, 2)) - disc.V.row(disc.F(f, 0)))
                  .transpose();
  EXPECT_GT(normal.x() / (2.0 * area), 0.95);  // measured 0.986: the rim follows the voxels
  const TriMesh back = interfaceOfLabels(s, 2, 1);
  EXPECT_EQ(back.F.rows(), disc.F.rows());
  EXPECT_NEAR(triangleAreas(back.V, back.F).sum(), area, 1e-9 * area);
  EXPECT_EQ(interfaceOfLabels(s, 1, 3).F.rows(), 0);
  EXPECT_THROW(interfaceOfLabels(s, 1, 1), UsageError);
  EXPECT_THROW(interfaceOfLabels(s, 1, 42), UsageError);
}

// One conforming tet mesh of the three labels: each label's tets fill exactly what its surface encloses.
TEST(SharedLabelSurfaces, TouchingLabelsGiveOneConformingTetMesh) {
  const SharedLabelSurfaces s = sharedLabelSurfaces(splitBall(), {});
  const TetMesh mesh = tetrahedralizeLabels(s);
  const TetQualityReport q = tetQualityReport(mesh.V, mesh.T);
  EXPECT_EQ(q.inverted, 0);
  EXPECT_EQ(q.degenerate, 0);
  EXPECT_GE(q.minDihedral, 5.0);
  const io::TetMeshSummary summary = io::summarize(mesh);
  ASSERT_EQ(summary.volumePerLabel.size(), 3u);
  for (Label id : s.ids) {
    const TriMesh own = surfaceOfLabel(s, id);
    EXPECT_NEAR(summary.volumePerLabel.at(id) / enclosedVolume(own.V, own.F), 1.0, 1e-5) << id;
  }
}

TEST(SharedLabelSurfaces, DiagonalContactsAreRepairedIntoManifolds) {
  GridGeometry g;
  g.size = Eigen::Vector3i(6, 6, 6);
  LabelMap map;
  map.labels = Grid<Label>(g, 0);
  map.labels.at(1, 1, 1) = map.labels.at(2, 2, 1) = 4;  // meet across an edge
  map.labels.at(3, 3, 3) = map.labels.at(4, 4, 4) = 5;  // meet at a corner
  map.labels.at(2, 1, 1) = 6;                           // takes one of label 4's bridges
  const SharedLabelSurfaces s = sharedLabelSurfaces(map, {});
  EXPECT_GE(s.repairedVoxels, 3);
  for (Label id : s.ids) expectClosedAndClean(surfaceOfLabel(s, id), "label " + std::to_string(id));
}

TEST(SharedLabelSurfaces, RefusesWhatItCannotMesh) {
  const LabelMap map = splitBall();
  EXPECT_THROW(sharedLabelSurfaces(map, {42}), BadInput);
  EXPECT_THROW(sharedLabelSurfaces(map, {}, {-1}), UsageError);
  EXPECT_THROW(surfaceOfLabel(sharedLabelSurfaces(map, {1}), 2), UsageError);
}

// All labels of TotalSegmentator's map of the test CT (3 mm voxels): organs, bones and muscles, many
// of them touching.
TEST(SharedLabelSurfaces, EveryLabelOfTheTestCtIsClosedAndTouchingOnesShareFaces) {
  const std::string data = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";
  const LabelMap map =
      io::readLabelMap(data + "example_seg_total_v1_for_example_ct.nii.gz", data + "labels_total_v1.tsv");
  const SharedLabelSurfaces s = sharedLabelSurfaces(map, {});
  EXPECT_EQ(s.ids.size(), 59u);
  EXPECT_TRUE(selfIntersections(s.V, s.F).empty());
  long shared = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) shared += s.sides(f, 0) != 0 && s.sides(f, 1) != 0;
  RecordProperty("shared_triangles", std::to_string(shared));
  RecordProperty("repaired_voxels", std::to_string(s.repairedVoxels));
  EXPECT_GT(shared, 10000);
  long voxels = 0;
  for (Label l : map.labels.values) voxels += l != 0;
  EXPECT_LT(s.repairedVoxels, voxels / 100);
  for (Label id : s.ids) {
    const std::string name = map.table.find(id)->name;
    const TriMesh mesh = surfaceOfLabel(s, id);
    const EdgeCounts edges = countEdges(mesh.F);
    EXPECT_EQ(edges.boundary, 0) << name;
    EXPECT_EQ(edges.nonManifold, 0) << name;
    const double voxels = voxelVolume(map, id);
    // Every label keeps its voxel volume, thin ribs included (they gain voxels in the repairs); labels of
    // a voxel or three (cut by the scan's edge) have too few vertices of their own to give the volume back.
    if (voxels > 1000.0) {
      EXPECT_NEAR(enclosedVolume(mesh.V, mesh.F) / voxels, 1.0, 0.002) << name;
    }
  }
}

}  // namespace
}  // namespace vesalius::meshing
