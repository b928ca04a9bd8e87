// A bone mesh brought onto a bone label (patient/bone_onto_label.h) and midpoint subdivision
// (meshing/midpoint_subdivision.h). The labels are painted shapes the scan's grid cuts (as a CT's field of
// view cuts a femur), the bones coarse spheres of another size and place: the registered bone must take
// the label's shape inside the field of view (Dice ≥ 0.90, the label's boundary within a voxel of it) and
// go on beyond it.
#include "vesalius/patient/bone_onto_label.h"

#include "test_label_maps.h"
#include "test_shapes.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/midpoint_subdivision.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <map>

namespace vesalius::test {
namespace {

constexpr double kVoxel = 2.0;

// A grid of 2 mm voxels over x, y in [-60, 60] and z from `zMin` to 60: below zMin the scan does not see.
GridGeometry scanGrid(double zMin) {
  GridGeometry g;
  g.spacing = Eigen::Vector3d::Constant(kVoxel);
  g.origin = Eigen::Vector3d(-60, -60, zMin);
  g.size = Eigen::Vector3i(61, 61, int((60 - zMin) / kVoxel) + 1);
  return g;
}

struct Shape {
  std::string name;
  std::function<bool(const Eigen::Vector3d&)> inside;
  double lowest;  // mm: the shape's lowest z, below the field of view
};

std::vector<Shape> shapes() {
  return {{"ellipsoid 30x20x45 mm",
           [](const Eigen::Vector3d& p) { return std::pow(p.x() / 30, 2) + std::pow(p.y() / 20, 2) + std::pow(p.z() / 45, 2) <= 1; },
           -45},
          {"two balls (a head on a neck)",
           [](const Eigen::Vector3d& p) {
             return (p - Eigen::Vector3d(8, 0, 18)).norm() <= 22 || (p - Eigen::Vector3d(-4, 0, -15)).norm() <= 18;
           },
           -33}};
}

TEST(BoneOntoLabel, TakesTheLabelsShapeInsideTheFieldOfViewAndGoesOnBeyondIt) {
  for (const Shape& shape : shapes())
    for (const int levels : {1, 3}) {
      SCOPED_TRACE(shape.name + ", sphere of " + std::to_string(8 << (2 * levels)) + " triangles");
      LabelMap labels = paintedLabelMap(scanGrid(-20), [&](const Eigen::Vector3d& p) { return shape.inside(p) ? 7 : 0; });
      labels.table.entries.push_back({7, "bone", {}});
      const TriMesh bone = sphere(levels, 26.0, Eigen::Vector3d(6, -5, 4));
      const patient::BoneOntoLabel r = patient::registerBoneOntoLabel(bone, labels, {7}, {}, "sphere", "painted");
      const double dice = segmentation::diceCoefficient(meshing::meshInsideMask(r.mesh, labels.labels.geometry),
                                                        segmentation::maskOf(labels.labels, 7));
      const double lowest = r.mesh.V.col(2).minCoeff();
      std::cout << shape.name << ", " << bone.F.rows() << " triangles -> " << r.mesh.F.rows() << ": Dice " << dice
                << ", label boundary to bone " << r.boundaryToMeshMeanMm << " mm (max " << r.boundaryToMeshMaxMm
                << "), lowest point " << lowest << " mm (the shape's " << shape.lowest << ")\n";
      EXPECT_GE(dice, 0.90);
      EXPECT_LT(r.boundaryToMeshMeanMm, kVoxel);
      EXPECT_GT(r.verticesInFieldOfView, 0);
      // Beyond the cut the bone goes on (it is not flattened onto the scan's edge at z = -20).
      EXPECT_LT(lowest, -20 - 2 * kVoxel);
      EXPECT_EQ(r.mesh.F.rows(), bone.F.rows() << (2 * meshing::midpointLevelsFor(bone, 2.0)));
    }
}

TEST(BoneOntoLabel, ALabelWithoutVoxelsIsRefusedNamingTheLabels) {
  LabelMap labels = paintedLabelMap(scanGrid(-20), [](const Eigen::Vector3d&) { return 0; });
  labels.table.entries.push_back({7, "bone", {}});
  try {
    patient::registerBoneOntoLabel(sphere(2, 20.0), labels, {7}, {}, "sphere", "empty.nii.gz");
    FAIL() << "no throw";
  } catch (const BadInput& e) {
    std::cout << e.what() << '\n';
    EXPECT_EQ(e.file(), "empty.nii.gz");
  }
}

TEST(MidpointSubdivision, KeepsTheSurfaceClosedAndItsShape) {
  for (const int levels : {1, 2}) {
    const TriMesh coarse = sphere(1, 10.0);
    const TriMesh fine = meshing::subdivideMidpoints(coarse, levels);
    // Each level adds a vertex per edge (E = 3F/2 on a closed surface) and quadruples the faces.
    Eigen::Index v = coarse.V.rows(), f = coarse.F.rows();
    for (int l = 0; l < levels; ++l) v += 3 * f / 2, f *= 4;
    EXPECT_EQ(fine.V.rows(), v);
    EXPECT_EQ(fine.F.rows(), f);
    std::map<std::pair<int, int>, int> edges;
    for (Eigen::Index t = 0; t < fine.F.rows(); ++t)
      for (int k = 0; k < 3; ++k) ++edges[std::minmax(fine.F(t, k), fine.F(t, (k + 1) % 3))];
    for (const auto& [edge, count] : edges) ASSERT_EQ(count, 2);
    // Every new vertex lies on the coarse surface.
    double farthest = 0;
    const TriangleTree tree(coarse.V, coarse.F);
    for (const ClosestPoint& c : tree.closest(fine.V)) farthest = std::max(farthest, std::sqrt(c.squaredDistance));
    std::cout << levels << " levels: " << fine.V.rows() << " vertices, farthest from the coarse surface " << farthest << " mm\n";
    EXPECT_LT(farthest, 1e-9);
    // The outward orientation is kept: the enclosed volume has the coarse mesh's sign and size.
    EXPECT_NEAR(enclosedVolume(fine.V, fine.F), enclosedVolume(coarse.V, coarse.F), 1e-9 * std::abs(enclosedVolume(coarse.V, coarse.F)));
  }
  EXPECT_EQ(meshing::midpointLevelsFor(sphere(1, 10.0), 100.0), 0);
}

}  // namespace
}  // namespace vesalius::test
