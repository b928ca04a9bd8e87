// Marker files: the hand-written samples in testdata/markers (every position checked in LPS), round trips
// through every format, and the bad files in testdata/bad.
#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/text_file.h"

#include "expect_bad_input.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <utility>

namespace vesalius::io {
namespace {

const std::string kMarkers = std::string(VESALIUS_TESTDATA) + "/markers/";
const std::string kBad = std::string(VESALIUS_TESTDATA) + "/bad/";

std::string outputPath(const std::string& name) {
  std::filesystem::create_directories(VESALIUS_TEST_OUTPUT);
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/" + name;
  std::filesystem::remove(path);
  return path;
}

void expectAt(const Eigen::Vector3d& p, double l, double pp, double s) {
  EXPECT_NEAR(p.x(), l, 1e-9);
  EXPECT_NEAR(p.y(), pp, 1e-9);
  EXPECT_NEAR(p.z(), s, 1e-9);
}

// A marker from its first fields, in the order Marker declares them.
Marker marker(std::string label, MarkerKind kind, MarkerStatus status, Eigen::Vector3d position,
              std::optional<Eigen::Vector3d> templatePosition, std::string description, bool selected, bool locked,
              bool visible) {
  Marker m;
  m.label = std::move(label);
  m.kind = kind;
  m.status = status;
  m.position = position;
  m.templatePosition = templatePosition;
  m.description = std::move(description);
  m.selected = selected;
  m.locked = locked;
  m.visible = visible;
  return m;
}

// The scan geometry the .annot sample is read with (testdata/markers/SOURCE.md).
GridGeometry annotScan() {
  GridGeometry g;
  g.size = Eigen::Vector3i(100, 120, 40);
  g.origin = Eigen::Vector3d(-120.5, 80.25, -300);
  g.spacing = Eigen::Vector3d(0.8, 0.8, 2.5);
  g.direction << 0, 1, 0, -1, 0, 0, 0, 0, 1;  // columns: i -> -P, j -> +L, k -> +S
  return g;
}

TEST(SlicerMarkups, V103LpsWithUndefinedPointAndTemplatePosition) {
  const MarkerSet set = readMarkers(kMarkers + "slicer_v1.0.3_lps.mrk.json", {MarkerKind::Attachment, nullptr});
  ASSERT_EQ(set.markers.size(), 3u);
  const Marker& dome = set.markers[0];
  EXPECT_EQ(dome.label, "liver dome");
  EXPECT_EQ(dome.description, "highest point of the right lobe");
  EXPECT_EQ(dome.kind, MarkerKind::Attachment);  // unnamed markup: the caller's default
  EXPECT_EQ(dome.status, MarkerStatus::Defined);
  expectAt(dome.position, -62.25, 18.5, 1041.125);
  ASSERT_TRUE(dome.templatePosition.has_value());
  expectAt(*dome.templatePosition, 1.5, -2.25, 3.0);
  EXPECT_EQ(set.markers[1].label, "gallbladder fundus");
  EXPECT_EQ(set.markers[1].status, MarkerStatus::Undefined);
  EXPECT_FALSE(set.markers[1].selected);
  EXPECT_FALSE(set.markers[1].templatePosition.has_value());
  expectAt(set.markers[2].position, -41.0, 35.75, 988.5);
  EXPECT_TRUE(set.markers[2].locked);
  EXPECT_FALSE(set.markers[2].visible);
  EXPECT_EQ(set.countDefined(), 2u);
}

TEST(SlicerMarkups, RasIsConvertedAndMarkupNameGivesKind) {
  const MarkerSet set = readMarkers(kMarkers + "slicer_v1.0.3_ras_icp.mrk.json");
  ASSERT_EQ(set.markers.size(), 2u);
  EXPECT_EQ(set.count(MarkerKind::IcpMarker), 2u);
  expectAt(set.markers[0].position, -12.5, 30.25, 101.0);
  expectAt(set.markers[1].position, 7.125, 0.0, -3.5);
  EXPECT_EQ(set.markers[1].status, MarkerStatus::Preview);
}

TEST(SlicerMarkups, V100WithoutPositionStatusIsDefined) {
  const MarkerSet set = readMarkers(kMarkers + "slicer_v1.0.0_no_status.mrk.json");
  ASSERT_EQ(set.markers.size(), 2u);
  EXPECT_EQ(set.countDefined(), 2u);
  expectAt(set.markers[0].position, 3.0, -4.5, 60.25);
  expectAt(set.markers[1].position, -0.001, 0.001, -1200.5);
  EXPECT_EQ(set.markers[1].label, "F-2");
}

TEST(SlicerMarkups, WritesSchema103AsSlicerLaysItOut) {
  MarkerSet set;
  set.markers.push_back(marker("a", MarkerKind::IcpMarker, MarkerStatus::Defined, {1, -2, 3.5}, {}, "", true, false, true));
  const std::string text = formatSlicerMarkups(set);
  EXPECT_EQ(text.rfind("{\n    \"@schema\": \"https://raw.githubusercontent.com/slicer/slicer/master/Modules/Loadable/"
                       "Markups/Resources/Schema/markups-schema-v1.0.3.json#\",\n    \"markups\": [\n        {\n"
                       "            \"type\": \"Fiducial\",\n            \"name\": \"icp\",\n"
                       "            \"coordinateSystem\": \"LPS\",\n            \"coordinateUnits\": \"mm\",\n",
                       0),
            0u);
  EXPECT_NE(text.find("                    \"position\": [1.0, -2.0, 3.5],\n"), std::string::npos);
  EXPECT_NE(text.find("\"orientation\": [-1.0, -0.0, -0.0, -0.0, -1.0, -0.0, 0.0, 0.0, 1.0]"), std::string::npos);
  EXPECT_NE(text.find("\"positionStatus\": \"defined\"\n"), std::string::npos);
  EXPECT_NE(text.find("\"measurements\": [],\n"), std::string::npos);
}

TEST(Fcsv, Version46NumericRasFlagWithQuotedLabels) {
  const MarkerSet set = readMarkers(kMarkers + "fiducials_v4.6_flag0_ras_14col.fcsv", {MarkerKind::IcpMarker, nullptr});
  ASSERT_EQ(set.markers.size(), 2u);
  expectAt(set.markers[0].position, -10.5, 20.25, 30.0);
  expectAt(set.markers[1].position, 1.125, -2.5, -300.75);
  EXPECT_EQ(set.markers[0].label, "apex, left ventricle");
  EXPECT_EQ(set.markers[1].label, "say \"hi\", twice");
  EXPECT_EQ(set.markers[1].description, "second point");
  EXPECT_FALSE(set.markers[1].visible);
  EXPECT_TRUE(set.markers[1].locked);
  EXPECT_EQ(set.count(MarkerKind::IcpMarker), 2u);
}

TEST(Fcsv, Version48NumericLpsFlagWithCrlf) {
  const MarkerSet set = readMarkers(kMarkers + "fiducials_v4.8_flag1_lps_14col.fcsv");
  ASSERT_EQ(set.markers.size(), 1u);
  expectAt(set.markers[0].position, -5.0, 6.75, 70.5);
  EXPECT_EQ(set.markers[0].label, "left, right");
  EXPECT_FALSE(set.markers[0].selected);
}

TEST(Fcsv, Version410Ras) {
  const MarkerSet set = readMarkers(kMarkers + "fiducials_v4.10_ras_14col.fcsv");
  ASSERT_EQ(set.markers.size(), 2u);
  expectAt(set.markers[0].position, -100.25, 0.5, 12.0);
  expectAt(set.markers[1].position, 3.0, -4.0, -5.0);
  EXPECT_EQ(set.markers[1].description, "desc with spaces");
}

TEST(Fcsv, Version411SixteenColumnsCarryPositionStatus) {
  const MarkerSet set = readMarkers(kMarkers + "fiducials_v4.11_lps_16col.fcsv");
  ASSERT_EQ(set.markers.size(), 3u);
  EXPECT_EQ(set.markers[0].status, MarkerStatus::Defined);
  EXPECT_EQ(set.markers[1].status, MarkerStatus::Undefined);
  EXPECT_EQ(set.markers[2].status, MarkerStatus::Preview);
  expectAt(set.markers[0].position, -62.25, 18.5, 1041.125);
  expectAt(set.markers[2].position, -41.0, 35.75, 988.5);
  EXPECT_EQ(set.markers[0].label, "liver dome, right lobe");
  EXPECT_FALSE(set.markers[2].visible);
}

TEST(MarkerCsv, RasTableWithKindsAndStatuses) {
  const MarkerSet set = readMarkers(kMarkers + "markers_ras.csv", {MarkerKind::IcpMarker, nullptr});
  ASSERT_EQ(set.markers.size(), 3u);
  EXPECT_EQ(set.markers[0].label, "femoral head, right");
  expectAt(set.markers[0].position, 85.5, -20.25, -910.0);
  EXPECT_EQ(set.markers[0].kind, MarkerKind::Landmark);
  expectAt(set.markers[1].position, -1.5, 2.5, 3.75);
  EXPECT_EQ(set.markers[1].kind, MarkerKind::IcpMarker);
  EXPECT_EQ(set.markers[1].status, MarkerStatus::Defined);
  EXPECT_EQ(set.markers[2].kind, MarkerKind::Attachment);
  EXPECT_EQ(set.markers[2].status, MarkerStatus::Undefined);
}

TEST(ItkSnapAnnot, LandmarksMapThroughScanGeometry) {
  const GridGeometry scan = annotScan();
  const MarkerSet set = readMarkers(kMarkers + "itksnap_landmarks.annot", {MarkerKind::Landmark, &scan});
  ASSERT_EQ(set.markers.size(), 3u);  // the ruler (LineSegmentAnnotation) is not a marker
  EXPECT_EQ(set.markers[0].label, "apex");
  expectAt(set.markers[0].position, -104.5, 72.25, -292.5);
  EXPECT_EQ(set.markers[1].label, "base & <b> \"q\"");
  expectAt(set.markers[1].position, -72.3, 40.45, -251.25);
  EXPECT_EQ(set.markers[2].label, "origin voxel");
  expectAt(set.markers[2].position, -120.5, 80.25, -300.0);
}

TEST(ItkSnapAnnot, NeedsTheScanGeometry) {
  EXPECT_THROW(readMarkers(kMarkers + "itksnap_landmarks.annot"), BadInput);
  EXPECT_THROW(writeMarkers(outputPath("no_geometry.annot"), MarkerSet{}), UsageError);
}

MarkerSet sampleSet() {
  MarkerSet set;
  set.markers.push_back(marker("apex, \"left\"",
                         MarkerKind::Landmark,
                         MarkerStatus::Defined,
                         {1.0 / 3.0, -2e-7, 1234.5678901234},
                         Eigen::Vector3d(0.1, 0.2, 0.3),
                         "first, with comma",
                         true,
                         false,
                         true));
  set.markers.push_back(marker("icp-1",
                         MarkerKind::IcpMarker,
                         MarkerStatus::Defined,
                         {-10.25, 20.5, -30.125},
                         std::nullopt,
                         "",
                         false,
                         true,
                         false));
  set.markers.push_back(
      marker("unplaced", MarkerKind::Landmark, MarkerStatus::Undefined, {0, 0, 0}, std::nullopt, "", true, false, true));
  set.markers.push_back(marker("attach",
                         MarkerKind::Attachment,
                         MarkerStatus::Preview,
                         {7.0, 8.0, 9.0},
                         Eigen::Vector3d(-1, -2, -3),
                         "",
                         true,
                         false,
                         true));
  return set;
}

const Marker& byLabel(const MarkerSet& set, const std::string& label) {
  for (const Marker& m : set.markers)
    if (m.label == label) return m;
  throw std::runtime_error("no marker " + label);
}

TEST(RoundTrip, SlicerMarkupsKeepEverythingButUnplacedPositions) {
  const MarkerSet in = sampleSet();
  const std::string path = outputPath("round.mrk.json");
  writeMarkers(path, in);
  const MarkerSet out = readMarkers(path);
  ASSERT_EQ(out.markers.size(), in.markers.size());
  for (const Marker& m : in.markers) {
    const Marker& r = byLabel(out, m.label);
    EXPECT_EQ(r.kind, m.kind);
    EXPECT_EQ(r.status, m.status);
    EXPECT_EQ(r.description, m.description);
    EXPECT_EQ(r.selected, m.selected);
    EXPECT_EQ(r.locked, m.locked);
    EXPECT_EQ(r.visible, m.visible);
    EXPECT_EQ(r.templatePosition.has_value(), m.templatePosition.has_value());
    if (m.templatePosition) {
      EXPECT_EQ(*r.templatePosition, *m.templatePosition);
    }
    if (m.status != MarkerStatus::Undefined) {
      EXPECT_EQ(r.position, m.position);  // shortest round-trip digits; preview points keep theirs
    }
  }
}

TEST(RoundTrip, FcsvKeepsLabelsStatusesFlags) {
  const MarkerSet in = sampleSet();
  const std::string path = outputPath("round.fcsv");
  writeMarkers(path, in);
  EXPECT_EQ(readTextFile(path).rfind("# Markups fiducial file version = 4.11\n# CoordinateSystem = LPS\n", 0), 0u);
  const MarkerSet out = readMarkers(path, {MarkerKind::IcpMarker, nullptr});
  ASSERT_EQ(out.markers.size(), in.markers.size());
  for (std::size_t i = 0; i < in.markers.size(); ++i) {
    EXPECT_EQ(out.markers[i].label, in.markers[i].label);
    EXPECT_EQ(out.markers[i].description, in.markers[i].description);
    EXPECT_EQ(out.markers[i].status, in.markers[i].status);
    EXPECT_EQ(out.markers[i].kind, MarkerKind::IcpMarker);
    EXPECT_EQ(out.markers[i].selected, in.markers[i].selected);
    EXPECT_EQ(out.markers[i].locked, in.markers[i].locked);
    EXPECT_EQ(out.markers[i].visible, in.markers[i].visible);
    EXPECT_EQ(out.markers[i].position, in.markers[i].position);
  }
}

// A row whose id begins with '#' must not come back as a header line (found by fuzz_fcsv).
TEST(RoundTrip, FcsvKeepsAnIdThatBeginsWithAHash) {
  MarkerSet in = sampleSet();
  in.markers.front().id = "# sy";
  const MarkerSet out = io::parseFcsv(io::formatFcsv(in), "hash.fcsv", MarkerKind::Landmark);
  ASSERT_EQ(out.markers.size(), in.markers.size());
  EXPECT_EQ(out.markers.front().id, "# sy");
}

TEST(RoundTrip, CsvKeepsLabelsKindsStatuses) {
  const MarkerSet in = sampleSet();
  const std::string path = outputPath("round.csv");
  writeMarkers(path, in);
  EXPECT_EQ(readTextFile(path).rfind(
                "label,l,p,s,defined,selected,visible,locked,description,kind,status,id,associatedNodeID,color,tags\n", 0),
            0u);
  const MarkerSet out = readMarkers(path);
  ASSERT_EQ(out.markers.size(), in.markers.size());
  for (std::size_t i = 0; i < in.markers.size(); ++i) {
    EXPECT_EQ(out.markers[i].label, in.markers[i].label);
    EXPECT_EQ(out.markers[i].kind, in.markers[i].kind);
    EXPECT_EQ(out.markers[i].status, in.markers[i].status);
    if (in.markers[i].status != MarkerStatus::Undefined) {
      EXPECT_EQ(out.markers[i].position, in.markers[i].position);
    }
  }
}

TEST(RoundTrip, AnnotKeepsPlacedLandmarks) {
  const GridGeometry scan = annotScan();
  MarkerSet in = sampleSet();
  const std::string path = outputPath("round.annot");
  EXPECT_THROW(writeMarkers(path, in, {}, &scan), UsageError);  // unplaced markers have no place in .annot
  in.markers.erase(in.markers.begin() + 2, in.markers.end());
  writeMarkers(path, in, {}, &scan);
  const MarkerSet out = readMarkers(path, {MarkerKind::Landmark, &scan});
  ASSERT_EQ(out.markers.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(out.markers[i].label, in.markers[i].label);
    expectAt(out.markers[i].position, in.markers[i].position.x(), in.markers[i].position.y(),
             in.markers[i].position.z());
  }
}

TEST(MarkerIo, KeepsExistingOutputsUnlessForced) {
  const std::string path = outputPath("kept.csv");
  writeMarkers(path, sampleSet());
  EXPECT_THROW(writeMarkers(path, MarkerSet{}), UsageError);
  EXPECT_EQ(readMarkers(path).markers.size(), 4u);
  writeMarkers(path, MarkerSet{}, WriteOptions{true});
  EXPECT_EQ(readMarkers(path).markers.size(), 0u);
  EXPECT_TRUE(isMarkerFile("a/b.MRK.JSON"));
  EXPECT_FALSE(isMarkerFile("a/b.json"));
  EXPECT_THROW(writeMarkers(outputPath("markers.txt"), MarkerSet{}), UsageError);
}

TEST(MarkerIo, CsvFieldsSplitAsSlicerSplitsThem) {
  const LineReader reader("", "row.csv");
  const std::vector<std::string> f = splitCsvRow("a,\"b, c\",\"d \"\"e\"\"\",,x\"y", reader);
  ASSERT_EQ(f.size(), 5u);
  EXPECT_EQ(f[1], "b, c");
  EXPECT_EQ(f[2], "d \"e\"");
  EXPECT_EQ(f[3], "");
  EXPECT_EQ(f[4], "x\"y");
  EXPECT_EQ(quoteCsvField("d \"e\", f"), "\"d \"\"e\"\", f\"");
  EXPECT_THROW(quoteCsvField("two\nlines"), UsageError);
  EXPECT_THROW(splitCsvRow("a\rb,c", reader), BadInput);  // found by fuzz_fcsv
}

void expectBadInput(const std::string& path, const std::string& fragment) {
  const GridGeometry scan = annotScan();
  test::expectOneLineBadInput(path, fragment, [&] { readMarkers(path, {MarkerKind::Landmark, &scan}); });
}

TEST(MarkerIo, BadFilesAreOneLineBadInput) {
  expectBadInput(kBad + "markers_no_schema.mrk.json", "no \"@schema\"");
  expectBadInput(kBad + "markers_schema_v2.mrk.json", "unsupported \"@schema\"");
  expectBadInput(kBad + "markers_curve.mrk.json", "markup 1: markup type 'Curve'");
  expectBadInput(kBad + "markers_short_position.mrk.json", "control point 1: position must be an array of 3");
  expectBadInput(kBad + "markers_bad_status.mrk.json", "unknown positionStatus 'maybe' (defined, undefined, preview or missing)");
  expectBadInput(kBad + "markers_truncated.mrk.json", "invalid JSON");
  expectBadInput(kBad + "markers_ijk.fcsv", "line 2: IJK");
  expectBadInput(kBad + "markers_bad_number.fcsv", "line 4: bad y 'abc'");
  expectBadInput(kBad + "markers_slicer3_long_row.fcsv", "line 3: a Slicer 3 row (no version line) is label,x,y,z");
  expectBadInput(kBad + "markers_unclosed_quote.fcsv", "line 4: field 12 opens a quote that is never closed");
  expectBadInput(kBad + "markers_xyz_header.csv", "line 1: the header needs columns l,p,s");
  expectBadInput(kBad + "markers_bad_kind.csv", "line 3: unknown kind 'bone'");
  expectBadInput(kBad + "markers_short_row.csv", "line 2: expected at least 4 fields");
  expectBadInput(kBad + "markers_wrong_format.annot", "not an ITK-SNAP annotation file");
  expectBadInput(kBad + "markers_unclosed.annot", "<folder> is not closed");
  expectBadInput(kBad + "markers_short_pos.annot", "Pos must be three numbers");
  expectBadInput(kBad + "does_not_exist.fcsv", "cannot open");
  expectBadInput(kBad + "markers_no_schema.json", "unknown marker file extension");
}

}  // namespace
}  // namespace vesalius::io
