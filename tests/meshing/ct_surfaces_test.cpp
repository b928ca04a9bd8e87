// The scan -> labels -> surfaces -> picture slice of `vesalius demo` on the shipped CT: surfaces of the
// body and of the bone must be closed and enclose the volume of their voxels; the overlay PNG is written.
#include "vesalius/core/mesh_measures.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/viz/slice_overlay.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace vesalius {
namespace {

const std::string kCt = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/example_ct.nii.gz";

class DemoCt : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ct_ = new Image(io::readScan(kCt));
    tissues_ = new LabelMap(segmentation::segmentCtTissues(*ct_));
  }
  static void TearDownTestSuite() {
    delete ct_;
    delete tissues_;
  }
  static double voxelVolume(const LabelMap& map, Label id) {
    return double(segmentation::countVoxels(segmentation::maskOf(map.labels, id))) *
           map.labels.geometry.spacing.prod();
  }
  static Image* ct_;
  static LabelMap* tissues_;
};
Image* DemoCt::ct_ = nullptr;
LabelMap* DemoCt::tissues_ = nullptr;

TEST_F(DemoCt, BodySurfaceIsClosedOnePieceWithTheVoxelVolume) {
  const LabelMap body = segmentation::labelMapOf(segmentation::segmentCtBody(*ct_, {}), {1, "body"});
  // The body fills the field of view from the first to the last slice: padding must close it there.
  // Checked without the volume restoration, which would hide a shrinking surface.
  meshing::SurfaceOptions raw;
  raw.preserveVolume = false;
  const io::TriMeshSummary s = io::summarize(meshing::labelSurface(body, 1, raw));
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.components, 1);
  ASSERT_TRUE(s.volume.has_value());
  const double ratio = *s.volume / voxelVolume(body, 1);
  RecordProperty("body_raw_volume_ratio", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.02);
}

TEST_F(DemoCt, BoneSurfaceIsClosedWithTheVoxelVolume) {
  const double voxels = voxelVolume(*tissues_, segmentation::kCtBone);
  const TriMesh mesh = meshing::labelSurface(*tissues_, segmentation::kCtBone);
  const io::TriMeshSummary s = io::summarize(mesh);
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.selfIntersections, 0);
  ASSERT_TRUE(s.volume.has_value());
  RecordProperty("bone_volume_ratio", std::to_string(*s.volume / voxels));
  EXPECT_NEAR(*s.volume / voxels, 1.0, 0.002);
  // Without the volume restoration, thin ribs and processes lose about 2.6% to corner cuts and smoothing.
  meshing::SurfaceOptions raw;
  raw.preserveVolume = false;
  const double rawRatio =
      *io::summarize(meshing::labelSurface(*tissues_, segmentation::kCtBone, raw)).volume / voxels;
  RecordProperty("bone_raw_volume_ratio", std::to_string(rawRatio));
  EXPECT_NEAR(rawRatio, 1.0, 0.03);
}

// Bone in many thin pieces decimated to 30k triangles: closed, 2-manifold, free of crossings, and still the
// voxels' volume (the crumbs that decimation leaves out are too small to count).
TEST_F(DemoCt, DecimatedBoneStaysClosed) {
  meshing::SurfaceOptions options;
  options.targetFaces = 30000;
  const io::TriMeshSummary s = io::summarize(meshing::labelSurface(*tissues_, segmentation::kCtBone, options));
  EXPECT_LE(s.triangles, 33000);
  EXPECT_EQ(s.boundaryEdges, 0);
  EXPECT_EQ(s.nonManifoldEdges, 0);
  EXPECT_EQ(s.selfIntersections, 0);
  ASSERT_TRUE(s.volume.has_value());
  EXPECT_NEAR(*s.volume / voxelVolume(*tissues_, segmentation::kCtBone), 1.0, 0.02);
}

TEST_F(DemoCt, SurfacesLieInsideTheScanInWorldSpace) {
  const TriMesh mesh = meshing::labelSurface(*tissues_, segmentation::kCtSkin);
  const GridGeometry& g = ct_->geometry;
  for (Eigen::Index v = 0; v < mesh.V.rows(); v += 97) {
    const Eigen::Vector3d index = g.worldToIndex(mesh.V.row(v).transpose());
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(index[a], -1.0);
      EXPECT_LE(index[a], g.size[a]);
    }
  }
}

TEST_F(DemoCt, OverlayPngIsWritten) {
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/demo_overlay.png";
  std::filesystem::create_directories(VESALIUS_TEST_OUTPUT);
  viz::OverlayOptions options;
  options.write.force = true;
  viz::writeSliceOverlayPng(*ct_, *tissues_, path, options);
  EXPECT_GT(std::filesystem::file_size(path), 10000u);
}

}  // namespace
}  // namespace vesalius
