// The `vesalius` program end to end: what `info` says about the real test files, exit codes, one-line
// errors for bad input with no partial output, marker conversion, and --help on every subcommand.
#include "run_command.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;

struct InfoCase {
  std::string name, file;
  std::vector<std::string> facts;
};

class Info : public ::testing::TestWithParam<InfoCase> {};

TEST_P(Info, PrintsTheFacts) {
  const InfoCase& c = GetParam();
  const CommandResult r = runVesalius({"info", kData + "/" + c.file});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const std::string& fact : c.facts) expectContains(r.out, fact);
}

INSTANTIATE_TEST_SUITE_P(
    TestData, Info,
    ::testing::Values(
        InfoCase{"head_mri", "head-mri/ch2.nii.gz",
                 {"scan (NIfTI)", "181 x 217 x 181 voxels", "1 x 1 x 1 mm", "uint8", "values       0 .. 254"}},
        InfoCase{"ct", "ct-abdomen-pelvis/example_ct.nii.gz",
                 {"122 x 101 x 112 voxels", "3 x 3 x 3 mm", "orientation  RAS", "int32", "-1207 .. 3382"}},
        InfoCase{"dicom_series", "dicom/ct-series-jpeg2000", {"DICOM series", "512 x 512 x 20 voxels", "int16"}},
        InfoCase{"oblique", "oblique-ct/CT_pitch.nii.gz", {"175 x 248 x 58 voxels", "uint8"}},
        InfoCase{"liver_tets", "liver/liver.msh", {"tetrahedral mesh", "181", "596"}},
        InfoCase{"liver_surface", "liver/liver-smooth.obj", {"surface mesh", "2194", "4384", "closed"}},
        InfoCase{"muscle", "muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl", {"surface mesh", "30072"}},
        InfoCase{"pelvis_vtp", "skeleton-opensim/Geometry/r_pelvis.vtp", {"surface mesh", "122"}},
        InfoCase{"markers", "markers/slicer_v1.0.3_lps.mrk.json", {"markers", "landmarks", "undefined"}},
        InfoCase{"fcsv", "markers/fiducials_v4.11_lps_16col.fcsv", {"markers", "LPS"}},
        InfoCase{"cmu_motion", "motion/01_01.bvh", {"motion (BVH)", "joints       31", "frames       2752 at 120"}},
        InfoCase{"opensim", "skeleton-opensim/Rajagopal2016.osim",
                 {"OpenSim model", "bodies       22", "muscles      80 with 288 path points"}},
        InfoCase{"makehuman", "body/default.mhskel", {"MakeHuman skeleton", "bones        163"}},
        InfoCase{"label_table", "ct-abdomen-pelvis/labels_total_v1.tsv", {"label table, 104 labels", "liver"}}),
    [](const auto& info) { return info.param.name; });

// The bad inputs: one line naming the file, exit code 3.
struct BadCase {
  std::string name, file;
};

class BadInfo : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInfo, OneLineNamingTheFileAndExit3) {
  const std::string path = kData + "/bad/" + GetParam().file;
  const CommandResult r = runVesalius({"info", path});
  EXPECT_EQ(r.exitCode, 3) << r.err;
  expectContains(r.err, path);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(TestData, BadInfo,
                         ::testing::Values(BadCase{"truncated_nifti", "scan_truncated.nii.gz"},
                                           BadCase{"zero_spacing", "scan_zero_spacing.nii"},
                                           BadCase{"stl_nan", "mesh_nan_vertex.stl"},
                                           BadCase{"stl_nan_binary", "mesh_nan_vertex_binary.stl"},
                                           BadCase{"mrk_json_without_schema", "markers_no_schema.mrk.json"},
                                           BadCase{"bvh_missing_channel", "bvh_missing_channel.bvh"}),
                         [](const auto& info) { return info.param.name; });

// A motion whose frame lines outnumber its "Frames:" line is read with the declared count and one
// warning line on stderr naming the file.
TEST(Cli, MiscountedMotionIsReadWithOneWarningLine) {
  const std::string path = kData + "/motion/bvh_extra_frame_line.bvh";
  const CommandResult r = runVesalius({"info", path});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 0) << r.err;
  expectContains(r.out, "frames       2 at 10");
  expectContains(r.err, "warning: " + path + ": line 21: 1 frame line beyond 'Frames: 2' not read");
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// A label table names files: a name holding "../" or an absolute path still writes inside --out.
TEST(Cli, SurfaceNamesFromATableStayInTheOutputFolder) {
  const std::string dir = outputDir() + "/hostile_names", out = dir + "/surfaces";
  fs::remove_all(dir);
  fs::create_directories(dir);
  LabelMap map = io::readLabelMap(kData + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz",
                                  kData + "/ct-abdomen-pelvis/labels_total_v1.tsv");
  for (LabelEntry& e : map.table.entries) {
    if (e.name == "liver") e.name = "../escaped";
    if (e.name == "kidney_left") e.name = "/tmp/vesalius_escaped";
  }
  io::writeLabelMap(dir + "/labels.nii.gz", map, WriteOptions{true});
  const CommandResult r = runVesalius({"surface", "--labels", dir + "/labels.nii.gz", "--label", "../escaped",
                                       "--label", "/tmp/vesalius_escaped", "--out", out, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(fs::exists(out + "/___escaped.vtp"));
  EXPECT_TRUE(fs::exists(out + "/_tmp_vesalius_escaped.vtp"));
  EXPECT_FALSE(fs::exists(dir + "/escaped.vtp"));
  EXPECT_FALSE(fs::exists("/tmp/vesalius_escaped.vtp"));
}

TEST(Cli, DicomFolderWithTwoSeriesListsThem) {
  const CommandResult r = runVesalius({"info", kData + "/bad/dicom_two_series"});
  EXPECT_EQ(r.exitCode, 0) << r.err;
  expectContains(r.out, "2 series");
  const CommandResult segment = runVesalius(
      {"segment", "--scan", kData + "/bad/dicom_two_series", "--out", outputDir() + "/two.nii.gz", "--force"});
  EXPECT_EQ(segment.exitCode, 3);
  expectContains(segment.err, "series");
  EXPECT_FALSE(fs::exists(outputDir() + "/two.nii.gz"));
}

TEST(Cli, BadScanLeavesNoOutput) {
  const std::string out = outputDir() + "/truncated-labels.nii.gz";
  fs::remove(out);
  const CommandResult r =
      runVesalius({"segment", "--scan", kData + "/bad/scan_truncated.nii.gz", "--modality", "ct", "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(outputDir() + "/truncated-labels.tsv"));
}

TEST(Cli, AnExistingReportIsRefusedBeforeTheWork) {
  const std::string out = outputDir() + "/report-refused-labels.nii.gz", report = outputDir() + "/existing-report.json";
  fs::remove(out);
  std::ofstream(report) << "{}";
  const CommandResult r = runVesalius({"segment", "--scan", kData + "/ct-abdomen-pelvis/example_ct_sm.nii.gz",
                                       "--modality", "ct", "--out", out, "--report", report});
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(report), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, BadMarkersLeaveNoOutput) {
  const std::string out = outputDir() + "/no-schema.fcsv";
  fs::remove(out);
  const CommandResult r =
      runVesalius({"markers", "convert", kData + "/bad/markers_no_schema.mrk.json", "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  expectContains(r.err, "markers_no_schema.mrk.json");
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, MarkersConvertKeepsPositionsAndRefusesToOverwrite) {
  const std::string in = kData + "/markers/fiducials_v4.10_ras_14col.fcsv";
  const std::string out = outputDir() + "/converted.mrk.json";
  fs::remove(out);
  ASSERT_EQ(runVesalius({"markers", "convert", in, "--out", out}).exitCode, 0);
  const MarkerSet original = io::readMarkers(in), converted = io::readMarkers(out);
  ASSERT_EQ(original.markers.size(), converted.markers.size());
  for (std::size_t i = 0; i < original.markers.size(); ++i) {
    EXPECT_EQ(original.markers[i].label, converted.markers[i].label);
    EXPECT_LT((original.markers[i].position - converted.markers[i].position).norm(), 1e-9);
  }
  const CommandResult again = runVesalius({"markers", "convert", in, "--out", out});
  EXPECT_EQ(again.exitCode, 2);
  expectContains(again.err, "--force");
  EXPECT_EQ(runVesalius({"markers", "convert", in, "--out", out, "--force"}).exitCode, 0);
}

// Slicer 5.4's own file with a missing and an undefined point through .fcsv, .csv and back to .mrk.json:
// statuses, ids, labels and the one position kept, and `info` counts the statuses.
TEST(Cli, MarkersConvertCarriesSlicerStatusesAndIds) {
  const std::string in = kData + "/slicer-markups/slicer5.4_missing.mrk.json";
  const std::string fcsv = outputDir() + "/status.fcsv", csv = outputDir() + "/status.csv",
                    json = outputDir() + "/status.mrk.json";
  for (const std::string& p : {fcsv, csv, json}) fs::remove(p);
  const CommandResult toFcsv = runVesalius({"markers", "convert", in, "--out", fcsv});
  ASSERT_EQ(toFcsv.exitCode, 0) << toFcsv.err;
  expectContains(toFcsv.out, "3 markers (LPS), 2 without a position");
  ASSERT_EQ(runVesalius({"markers", "convert", fcsv, "--out", csv}).exitCode, 0);
  ASSERT_EQ(runVesalius({"markers", "convert", csv, "--out", json}).exitCode, 0);
  const MarkerSet original = io::readMarkers(in), back = io::readMarkers(json);
  ASSERT_EQ(back.markers.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back.markers[i].status, original.markers[i].status) << i;
    EXPECT_EQ(back.markers[i].id, original.markers[i].id) << i;
    EXPECT_EQ(back.markers[i].label, original.markers[i].label) << i;
    EXPECT_EQ(back.markers[i].locked, original.markers[i].locked) << i;
  }
  EXPECT_EQ(back.markers[1].position, original.markers[1].position);
  EXPECT_EQ(back.markers[0].status, MarkerStatus::Missing);
  const CommandResult info = runVesalius({"info", json});
  ASSERT_EQ(info.exitCode, 0) << info.err;
  expectContains(info.out, "1 defined, 1 undefined, 0 preview, 1 missing");
}

// ITK-SNAP colours and tags survive .annot -> .mrk.json -> .annot; .fcsv says it drops them.
TEST(Cli, MarkersConvertCarriesItkSnapColoursAndTags) {
  const std::string scan = kData + "/ct-abdomen-pelvis/example_ct_sm.nii.gz";
  const std::string in = kData + "/markers/itksnap4_color_tags.annot";
  const std::string json = outputDir() + "/tags.mrk.json", annot = outputDir() + "/tags.annot",
                    fcsv = outputDir() + "/tags.fcsv";
  for (const std::string& p : {json, annot, fcsv}) fs::remove(p);
  ASSERT_EQ(runVesalius({"markers", "convert", in, "--scan", scan, "--out", json}).exitCode, 0);
  ASSERT_EQ(runVesalius({"markers", "convert", json, "--scan", scan, "--out", annot}).exitCode, 0);
  const GridGeometry g = io::describeScan(scan).geometry;
  const MarkerSet original = io::readMarkers(in, {MarkerKind::Landmark, &g}),
                  back = io::readMarkers(annot, {MarkerKind::Landmark, &g});
  ASSERT_EQ(back.markers.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.markers[i].color, original.markers[i].color) << i;
    EXPECT_EQ(back.markers[i].tags, original.markers[i].tags) << i;
    EXPECT_LT((back.markers[i].position - original.markers[i].position).norm(), 1e-6) << i;
  }
  const CommandResult toFcsv = runVesalius({"markers", "convert", json, "--out", fcsv});
  ASSERT_EQ(toFcsv.exitCode, 0) << toFcsv.err;
  expectContains(toFcsv.out, "not kept by .fcsv: colours and tags");
}

TEST(Cli, MarkersWithAnUnclosedQuoteAreRefusedInOneLine) {
  const std::string in = kData + "/bad/markers_unclosed_quote.fcsv", out = outputDir() + "/unclosed.mrk.json";
  fs::remove(out);
  const CommandResult r = runVesalius({"markers", "convert", in, "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  expectContains(r.err, in + ": line 4: field 12 opens a quote that is never closed");
  EXPECT_FALSE(fs::exists(out));
}

TEST(Cli, SegmentThenSurfaceOneLabelByName) {
  const std::string labels = outputDir() + "/ct-labels.nii.gz", bone = outputDir() + "/bone.stl";
  ASSERT_EQ(runVesalius({"segment", "--scan", kData + "/ct-abdomen-pelvis/example_ct_sm.nii.gz", "--modality", "ct",
                         "--out", labels, "--force", "--progress", "none"})
                .exitCode,
            0);
  EXPECT_TRUE(fs::exists(outputDir() + "/ct-labels.png"));
  const CommandResult r =
      runVesalius({"surface", "--labels", labels, "--label", "bone", "--out", bone, "--force", "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::TriMeshSummary summary = io::summarize(io::readTriMesh(bone));
  EXPECT_TRUE(summary.closed);
  ASSERT_TRUE(summary.volume.has_value());
  EXPECT_GT(*summary.volume, 0.0);
  EXPECT_EQ(runVesalius({"surface", "--labels", labels, "--label", "liver", "--out", bone, "--force"}).exitCode, 2);
}

TEST(Cli, UsageErrorsExit2) {
  EXPECT_EQ(runVesalius({}).exitCode, 2);
  EXPECT_EQ(runVesalius({"frobnicate"}).exitCode, 2);
  EXPECT_EQ(runVesalius({"segment", "--scan"}).exitCode, 2);
  EXPECT_EQ(runVesalius({"info", kData + "/bad/scan_unknown_extension.xyz"}).exitCode, 3);
}

TEST(Cli, EveryCommandHasHelpWithAnExample) {
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{"info"}, {"segment"}, {"surface"}, {"markers", "convert"}, {"demo"}, {"patient"}}) {
    std::vector<std::string> args = command;
    args.push_back("--help");
    const CommandResult r = runVesalius(args);
    EXPECT_EQ(r.exitCode, 0) << command[0];
    expectContains(r.out, "Example");
    expectContains(r.out, "vesalius " + command[0]);
  }
}

}  // namespace
}  // namespace vesalius::test
