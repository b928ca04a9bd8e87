// 3D Slicer's and ITK-SNAP's label files through the `vesalius` program: `info` on them, `surface --label
// <segment name>` on a .seg.nrrd Slicer wrote, overlapping segments refused, `labels` reading a .seg.nrrd,
// and `segment --out labels.seg.nrrd` read back with the names and colours of the tissue table.
#include "run_command.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/label_table_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/slicer_segmentation.h"
#include "vesalius/segmentation/ct_tissues.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
const std::string kSeg = kData + "/slicer/Segmentation.seg.nrrd";
const std::string kOverlapping = kData + "/slicer/SegmentationOverlapping.seg.nrrd";

std::string fresh(const std::string& name) {
  const fs::path path = fs::path(outputDir()) / name;
  fs::remove(path);
  for (const std::string& table : io::labelTableSidecarPaths(path.string())) fs::remove(table);
  return path.string();
}

TEST(CliSlicerLabels, InfoDescribesSegmentationsAndTheirTables) {
  CommandResult r = runVesalius({"info", kSeg});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out;
  expectContains(r.out, "3D Slicer segmentation, 7 segments in 1 layer");
  expectContains(r.out, "128 x 128 x 34 voxels");
  expectContains(r.out, "8487  253 232 158  ribs");
  expectContains(r.out, "154589  128 174 128  tissue");

  r = runVesalius({"info", kOverlapping});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectContains(r.out, "8 segments in 2 layers");
  expectContains(r.out, "'left lung' and 'overlapping sphere' share 8723 voxels");

  // A Slicer colour CSV is a label table, not a marker table; ITK-SNAP's file is one too.
  for (const auto& [file, count] : std::vector<std::pair<std::string, std::string>>{
           {"slicer/ColorTest.csv", "3"}, {"slicer/ColorTestWithTerminology.csv", "4"},
           {"itksnap/MRIcrop-seg.label", "11"}, {"slicer/ColorTest.ctbl", "2"}}) {
    r = runVesalius({"info", kData + "/" + file});
    ASSERT_EQ(r.exitCode, 0) << file << ": " << r.err;
    expectContains(r.out, "label table, " + count + " labels");
  }
}

// Every vertex of a label's surface lies within the world box of that label's voxels (plus one voxel).
void expectWithinLabel(const TriMesh& mesh, const LabelMap& map, Label id, const std::string& what) {
  const GridGeometry& g = map.labels.geometry;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (int k = 0, n = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i, ++n)
        if (map.labels.values[std::size_t(n)] == id) {
          const Eigen::Vector3d p = g.indexToWorld(Eigen::Vector3d(i, j, k));
          low = low.cwiseMin(p);
          high = high.cwiseMax(p);
        }
  const double slack = g.spacing.maxCoeff();
  double outside = 0;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = mesh.V.row(v).transpose();
    outside = std::max({outside, (low - p).maxCoeff(), (p - high).maxCoeff()});
  }
  std::cout << what << ": " << mesh.V.rows() << " vertices, farthest " << outside << " mm beyond the label's box\n";
  EXPECT_GT(mesh.F.rows(), 100) << what;
  EXPECT_LE(outside, slack) << what;
}

TEST(CliSlicerLabels, SurfaceFindsASegmentByName) {
  const LabelMap map = io::readLabelMap(kSeg);
  for (const auto& [name, id] : std::vector<std::pair<std::string, Label>>{{"ribs", 1}, {"right lung", 5}}) {
    const std::string byName = fresh("seg-" + std::to_string(id) + "-by-name.stl");
    const std::string byId = fresh("seg-" + std::to_string(id) + "-by-id.stl");
    CommandResult r = runVesalius({"surface", "--labels", kSeg, "--label", name, "--out", byName, "--progress", "none"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    r = runVesalius(
        {"surface", "--labels", kSeg, "--label", std::to_string(id), "--out", byId, "--progress", "none"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const TriMesh a = io::readTriMesh(byName), b = io::readTriMesh(byId);
    EXPECT_TRUE(a.V.rows() == b.V.rows() && a.V == b.V) << name << ": the name and the id gave different surfaces";
    expectWithinLabel(a, map, id, name);
  }
}

// `tetmesh` meshes a segment chosen by name; its tets keep the segment's voxel volume (label_surface.h).
TEST(CliSlicerLabels, TetmeshMeshesASegmentByName) {
  const std::string out = fresh("left-lung.vtu");
  const CommandResult r = runVesalius({"tetmesh", "--labels", kSeg, "--label", "left lung", "--quality", "0",
                                       "--out", out, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::TetMeshSummary s = io::summarize(io::readTetMesh(out));
  ASSERT_EQ(s.tetsPerLabel.size(), 1u);
  ASSERT_EQ(s.tetsPerLabel.count(6), 1u);  // "left lung" is Segment5_LabelValue 6
  const LabelMap map = io::readLabelMap(kSeg);
  const double voxelVolume = double(std::count(map.labels.values.begin(), map.labels.values.end(), 6)) *
                             map.labels.geometry.spacing.prod();
  std::cout << "left lung: " << s.tetsPerLabel.at(6) << " tets, " << s.volumePerLabel.at(6) << " mm^3 of "
            << voxelVolume << " mm^3 of voxels\n";
  EXPECT_NEAR(s.volumePerLabel.at(6) / voxelVolume, 1.0, 0.02);
}

TEST(CliSlicerLabels, OverlappingSegmentsAreRefusedWithTheirNames) {
  const std::string out = fresh("overlap-ribs.stl");
  const CommandResult r =
      runVesalius({"surface", "--labels", kOverlapping, "--label", "ribs", "--out", out, "--progress", "none"});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  expectContains(r.err, kOverlapping + ": segments overlap");
  expectContains(r.err, "'overlapping sphere'");
  EXPECT_FALSE(fs::exists(out));
}

// `labels` reads a .seg.nrrd by segment name and writes a label map with the three tables beside it.
TEST(CliSlicerLabels, LabelsExtractsASegmentByName) {
  const std::string out = fresh("left-lung.nii.gz");
  const CommandResult r = runVesalius(
      {"labels", "extract", "--labels", kSeg, "--label", "left lung", "--out", out, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const LabelMap in = io::readLabelMap(kSeg), extracted = io::readLabelMap(out);
  const auto voxels = std::count(extracted.labels.values.begin(), extracted.labels.values.end(), 6);
  EXPECT_EQ(voxels, 33700);  // Segment5 of the file
  // Slicer's .ctbl cannot hold a space in a name and writes '_' (Slicer shows it as a space again).
  const std::vector<std::string> tables = io::labelTableSidecarPaths(out);
  ASSERT_EQ(tables.size(), 3u);
  const std::vector<std::string> names{"left lung", "left_lung", "left lung"};
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const LabelTable t = io::readLabelTable(tables[k]);
    ASSERT_NE(t.find(6), nullptr) << tables[k];
    EXPECT_EQ(t.find(6)->name, names[k]) << tables[k];
    EXPECT_EQ(t.find(6)->color, in.table.find(6)->color) << tables[k];
  }
}

// `segment --out X.seg.nrrd`: the same labels as the NIfTI output, named and coloured by the tissue table.
TEST(CliSlicerLabels, SegmentWritesASlicerSegmentation) {
  const std::string scan = kData + "/ct-abdomen-pelvis/example_ct_sm.nii.gz";
  const std::string seg = fresh("tissues-slicer.seg.nrrd"), nifti = fresh("tissues-nifti.nii.gz");
  CommandResult r = runVesalius({"segment", "--scan", scan, "--modality", "ct", "--out", seg, "--force", "--progress",
                                 "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVesalius({"segment", "--scan", scan, "--modality", "ct", "--out", nifti, "--force", "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const char* table : {"tissues-slicer.tsv", "tissues-slicer.ctbl", "tissues-slicer.label.txt"})
    EXPECT_FALSE(fs::exists(fs::path(outputDir()) / table)) << table;  // the .seg.nrrd carries its table
  for (const std::string& table : io::labelTableSidecarPaths(nifti)) EXPECT_TRUE(fs::exists(table)) << table;
  const io::SlicerSegmentation file = io::readSlicerSegmentation(seg);
  const LabelMap fromSeg = io::readLabelMap(seg), fromNifti = io::readLabelMap(nifti);
  EXPECT_EQ(fromSeg.labels.values, fromNifti.labels.values);
  const LabelTable tissues = segmentation::ctTissueTable(false);
  ASSERT_EQ(file.segments.size(), tissues.entries.size());
  for (std::size_t s = 0; s < file.segments.size(); ++s) {
    EXPECT_EQ(file.segments[s].name, tissues.entries[s].name);
    EXPECT_EQ(file.segments[s].labelValue, tissues.entries[s].id);
    EXPECT_EQ(file.segments[s].color, tissues.entries[s].color) << tissues.entries[s].name;
    EXPECT_EQ(file.segments[s].layer, 0);
  }
  const std::string bone = fresh("tissues-bone.stl");
  r = runVesalius({"surface", "--labels", seg, "--label", "bone", "--out", bone, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectWithinLabel(io::readTriMesh(bone), fromSeg, segmentation::kCtBone, "bone from the .seg.nrrd");
}

}  // namespace
}  // namespace vesalius::test
