// `vesalius tetmesh` end to end: a Visible Human muscle, two labels of the test CT and a body with a bone
// inside become tet meshes with the volume they should have; touching labels (--shared) share their
// boundaries, in surfaces and in one tet mesh; an open and a self-intersecting surface are refused with
// exit 3 and one line, writing nothing; `vesalius info` counts self-intersections.
#include "run_command.h"
#include "test_label_maps.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/tet_locator.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <filesystem>
#include <regex>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;

std::string outputPath(const std::string& name) {
  const fs::path dir = fs::path(VESALIUS_TEST_OUTPUT) / "tetmesh";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return (dir / name).string();
}

double printedMinDihedral(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("dihedral angles  min ([0-9.]+) deg"))) return -1;
  return std::stod(m[1]);
}

// A label map of 2 mm voxels with soft tissue (1) and bone (5), labelled by a function of the voxel index.
LabelMap softAndBone(const Eigen::Vector3i& size, const std::function<Label(const Eigen::Vector3d&)>& labelAt) {
  GridGeometry g;
  g.size = size;
  g.spacing = {2, 2, 2};
  LabelMap map = paintedLabelMap(g, [&](const Eigen::Vector3d& p) { return labelAt(p / 2.0); });  // p = 2 index
  map.table.add({1, "soft", {200, 100, 100}});
  map.table.add({5, "bone", {240, 220, 150}});
  return map;
}

TEST(CliTetmesh, MuscleSurface) {
  const std::string surface = kData + "/muscles/VHF_Left_Muscle_GluteusMinimus_smooth.stl";
  const std::string out = outputPath("gluteus_minimus.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--surface", surface, "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_GE(printedMinDihedral(r.out), 10.0) << r.out;
  EXPECT_NE(r.out.find("inverted 0, flat 0"), std::string::npos) << r.out;
  const io::TetMeshSummary s = io::summarize(io::readTetMesh(out));
  const TriMesh input = io::readTriMesh(surface);
  EXPECT_GT(s.tets, 10000);
  EXPECT_EQ(s.inverted, 0);
  EXPECT_EQ(s.tetsPerLabel.size(), 1u);
  EXPECT_NEAR(s.totalVolume / enclosedVolume(input.V, input.F), 1.0, 1e-6);
}

TEST(CliTetmesh, TwoLabelsOfTheCtGiveTwoRegions) {
  const std::string labels = kData + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz";
  const std::string table = kData + "/ct-abdomen-pelvis/labels_total_v1.tsv";
  const std::string out = outputPath("gluteus_medius.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--labels", labels, "--table", table, "--label",
                                       "gluteus_medius_left", "--label", "gluteus_medius_right", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_GE(printedMinDihedral(r.out), 10.0) << r.out;
  const io::TetMeshSummary s = io::summarize(io::readTetMesh(out));
  ASSERT_EQ(s.tetsPerLabel.size(), 2u);
  EXPECT_GT(s.tetsPerLabel.at(96), 1000);
  EXPECT_GT(s.tetsPerLabel.at(97), 1000);
  // The label surfaces keep their voxels' volume (label_surface.h), so the tets do too.
  const LabelMap map = io::readLabelMap(labels, table);
  const auto voxels = std::count_if(map.labels.values.begin(), map.labels.values.end(),
                                    [](Label l) { return l == 96 || l == 97; });
  const double voxelVolume = double(voxels) * map.labels.geometry.spacing.prod();
  RecordProperty("volume_ratio", std::to_string(s.totalVolume / voxelVolume));
  EXPECT_NEAR(s.totalVolume / voxelVolume, 1.0, 0.02);
}

// A ball of soft tissue (label 1) around a ball of bone (label 5), 2 mm voxels, with an air pocket (label 0)
// in the soft tissue: --body meshes the union, holes filled, as the outer region with the bone nested
// inside it (Sujar et al. 2018, §3.2).
TEST(CliTetmesh, BodyWithABoneInside) {
  long pocketVoxels = 0;  // air inside, which the body keeps
  const LabelMap map = softAndBone({30, 30, 30}, [&](const Eigen::Vector3d& p) {
    const double r = (p - Eigen::Vector3d::Constant(14.5)).norm();
    const bool air = (p - Eigen::Vector3d(23.5, 14.5, 14.5)).norm() < 2.0;
    pocketVoxels += air && r < 12;
    return Label(r < 6 ? 5 : (r < 12 && !air ? 1 : 0));
  });
  const long bone = std::count(map.labels.values.begin(), map.labels.values.end(), 5);
  const long soft = std::count(map.labels.values.begin(), map.labels.values.end(), 1) + pocketVoxels;
  const std::string labels = outputPath("ball.nii.gz");
  for (const std::string& table : io::labelTableSidecarPaths(labels)) fs::remove(table);
  io::writeLabelMap(labels, map);
  const std::string out = outputPath("ball.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--labels", labels, "--label", "bone", "--body", "1", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_GE(printedMinDihedral(r.out), 10.0) << r.out;
  const TetMesh mesh = io::readTetMesh(out);
  const Eigen::VectorXd volumes = tetVolumes(mesh.V, mesh.T);
  const Eigen::VectorXi& label = mesh.tetAttributes.integer.at(kLabel);
  double softVolume = 0, boneVolume = 0;
  for (Eigen::Index t = 0; t < volumes.size(); ++t) (label(t) == 5 ? boneVolume : softVolume) += volumes(t);
  EXPECT_TRUE(((label.array() == 1) || (label.array() == 5)).all());
  const auto pocket = TetLocator(mesh.V, mesh.T).locate(Eigen::Vector3d(47, 29, 29));  // voxel (23.5, 14.5, 14.5)
  ASSERT_TRUE(pocket.has_value()) << "the air pocket was left out of the body";
  EXPECT_EQ(label(pocket->tet), 1);
  // The surfaces keep their voxels' volume (label_surface.h).
  EXPECT_NEAR(boneVolume / (8.0 * double(bone)), 1.0, 0.02);
  EXPECT_NEAR(softVolume / (8.0 * double(soft)), 1.0, 0.02);
}

// The sacrum and the fifth lumbar vertebra of the test CT touch: with --shared, `surface` gives them the
// same triangles where they meet, and `tetmesh` one conforming mesh with both volumes kept.
TEST(CliTetmesh, TouchingLabelsShareTheirBoundary) {
  const std::string labels = kData + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz";
  const std::string table = kData + "/ct-abdomen-pelvis/labels_total_v1.tsv";
  const std::string folder = (fs::path(VESALIUS_TEST_OUTPUT) / "tetmesh" / "spine").string();
  fs::remove_all(folder);
  fs::create_directories(fs::path(folder).parent_path());
  CommandResult r = runVesalius({"surface", "--labels", labels, "--table", table, "--label", "sacrum", "--label",
                                 "vertebrae_L5", "--shared", "--out", folder});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const TriMesh sacrum = io::readTriMesh(folder + "/sacrum.vtp"), l5 = io::readTriMesh(folder + "/vertebrae_L5.vtp");
  std::vector<std::array<double, 3>> points;
  for (Eigen::Index v = 0; v < sacrum.V.rows(); ++v) points.push_back({sacrum.V(v, 0), sacrum.V(v, 1), sacrum.V(v, 2)});
  std::sort(points.begin(), points.end());
  long common = 0;
  for (Eigen::Index v = 0; v < l5.V.rows(); ++v)
    common += std::binary_search(points.begin(), points.end(), std::array<double, 3>{l5.V(v, 0), l5.V(v, 1), l5.V(v, 2)});
  EXPECT_GT(common, 30);  // the joint's vertices, bit for bit
  for (const TriMesh* m : {&sacrum, &l5}) EXPECT_TRUE(io::summarize(*m).closed);

  const std::string out = outputPath("spine.vtu");
  r = runVesalius({"tetmesh", "--labels", labels, "--table", table, "--label", "sacrum", "--label", "vertebrae_L5",
                   "--shared", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // Where the joint meets the outside, the two bones' surfaces and the joint form thin wedges whose
  // angles no tet inside them can beat (tetrahedralize.h); 8 to 10.6 degrees here as smoothing was tuned.
  EXPECT_GE(printedMinDihedral(r.out), 6.0) << r.out;
  const io::TetMeshSummary s = io::summarize(io::readTetMesh(out));
  EXPECT_EQ(s.inverted, 0);
  ASSERT_EQ(s.volumePerLabel.size(), 2u);
  const LabelMap map = io::readLabelMap(labels, table);
  for (const auto& [name, surface] : {std::pair{"sacrum", &sacrum}, std::pair{"vertebrae_L5", &l5}}) {
    const Label id = map.table.resolve(name);
    const double voxels = double(std::count(map.labels.values.begin(), map.labels.values.end(), id)) *
                          map.labels.geometry.spacing.prod();
    EXPECT_NEAR(s.volumePerLabel.at(id) / voxels, 1.0, 0.02) << name;
    EXPECT_NEAR(s.volumePerLabel.at(id) / enclosedVolume(surface->V, surface->F), 1.0, 1e-5) << name;
  }
}

// A bone poking out of the body (as where a bone meets the skin or the scan's edge): with --body and
// --shared the bone keeps its whole volume and the body the rest, the two touching at the surface.
TEST(CliTetmesh, BoneReachingTheBodySurfaceKeepsItsVolume) {
  const LabelMap map = softAndBone({34, 30, 30}, [](const Eigen::Vector3d& p) {
    if ((p - Eigen::Vector3d(24.5, 14.5, 14.5)).norm() < 6) return Label(5);
    return Label((p - Eigen::Vector3d::Constant(14.5)).norm() < 12 ? 1 : 0);
  });
  const long bone = std::count(map.labels.values.begin(), map.labels.values.end(), 5);
  const long soft = std::count(map.labels.values.begin(), map.labels.values.end(), 1);
  const std::string labels = outputPath("poking.nii.gz");
  for (const std::string& table : io::labelTableSidecarPaths(labels)) fs::remove(table);
  io::writeLabelMap(labels, map);
  const std::string out = outputPath("poking.vtu");
  const CommandResult r =
      runVesalius({"tetmesh", "--labels", labels, "--label", "bone", "--body", "1", "--shared", "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::TetMeshSummary s = io::summarize(io::readTetMesh(out));
  EXPECT_EQ(s.inverted, 0);
  ASSERT_EQ(s.volumePerLabel.size(), 2u);
  EXPECT_NEAR(s.volumePerLabel.at(5) / (8.0 * double(bone)), 1.0, 0.02);
  EXPECT_NEAR(s.volumePerLabel.at(1) / (8.0 * double(soft)), 1.0, 0.02);
  EXPECT_EQ(runVesalius({"tetmesh", "--surface", labels, "--shared", "--out", out}).exitCode, 2);
}

// A map longer than Sujar et al.'s cap (250 voxels along L) is resampled before meshing and keeps its volume.
TEST(CliTetmesh, LabelMapOverTheSizeCapIsResampled) {
  GridGeometry g;
  g.size = {300, 30, 30};
  LabelMap map{Grid<Label>(g), {}};
  map.table.add({2, "rod", {200, 100, 100}});
  long voxels = 0;
  for (int k = 0; k < 30; ++k)
    for (int j = 0; j < 30; ++j)
      for (int i = 20; i < 280; ++i)
        if (Eigen::Vector2d(j - 14.5, k - 14.5).norm() < 10) map.labels.at(i, j, k) = 2, ++voxels;
  const std::string labels = outputPath("rod.nii.gz");
  for (const std::string& table : io::labelTableSidecarPaths(labels)) fs::remove(table);
  io::writeLabelMap(labels, map);
  const std::string out = outputPath("rod.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--labels", labels, "--out", out});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectContains(r.out, "label map resampled from 300x30x30 to 250x30x30 voxels");
  const io::TetMeshSummary s = io::summarize(io::readTetMesh(out));
  EXPECT_NEAR(s.totalVolume / double(voxels), 1.0, 0.03);
}

TEST(CliTetmesh, OpenSurfaceIsRefusedInOneLine) {
  TriMesh open = io::readTriMesh(kData + "/liver/liver.obj");
  open.F.conservativeResize(open.F.rows() - 1, 3);
  const std::string surface = outputPath("open_liver.obj");
  io::writeTriMesh(surface, open);
  const std::string out = outputPath("open_liver.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--surface", surface, "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(r.err, "vesalius: " + surface + ": open surface (3 boundary edges); a tet mesh needs a closed surface\n");
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliTetmesh, SelfIntersectingSurfaceIsRefused) {
  const std::string surface = kData + "/liver/liver-smooth.obj";
  const std::string out = outputPath("liver_smooth.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--surface", surface, "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(r.err.rfind("vesalius: " + surface + ": self-intersecting surface: 7 pairs", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliTetmesh, InfoReportsSelfIntersections) {
  const CommandResult crossed = runVesalius({"info", kData + "/liver/liver-smooth.obj"});
  ASSERT_EQ(crossed.exitCode, 0) << crossed.err;
  EXPECT_NE(crossed.out.find("self-intersections: 7 pairs of crossing triangles"), std::string::npos) << crossed.out;
  const CommandResult clean = runVesalius({"info", kData + "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl"});
  ASSERT_EQ(clean.exitCode, 0) << clean.err;
  EXPECT_NE(clean.out.find("self-intersections: 0 pairs"), std::string::npos) << clean.out;
}

TEST(CliTetmesh, HelpHasAnExample) {
  const CommandResult r = runVesalius({"tetmesh", "--help"});
  EXPECT_EQ(r.exitCode, 0);
  EXPECT_NE(r.out.find("vesalius tetmesh --surface"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace vesalius::test
