// Markers as 3D Slicer and ITK-SNAP write them: Slicer's own files (testdata/slicer-markups), the four
// position statuses, Slicer 3 lists, Slicer's markups table, ids, names, colours and tags carried
// between formats, our .mrk.json checked against Slicer's published schema and against the control
// points Slicer 5.4 wrote, and round trips that give back the same file.
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"
#include "vesalius/io/text_file.h"

#include "expect_bad_input.h"
#include "json_schema_subset.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <functional>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

namespace vesalius::io {
namespace {

const std::string kSlicer = std::string(VESALIUS_TESTDATA) + "/slicer-markups/";
const std::string kMarkers = std::string(VESALIUS_TESTDATA) + "/markers/";
const std::string kBad = std::string(VESALIUS_TESTDATA) + "/bad/";

using OrderedJson = nlohmann::ordered_json;

void expectAt(const Eigen::Vector3d& p, double l, double pp, double s) {
  EXPECT_NEAR(p.x(), l, 1e-12);
  EXPECT_NEAR(p.y(), pp, 1e-12);
  EXPECT_NEAR(p.z(), s, 1e-12);
}

GridGeometry annotScan() {  // as in testdata/markers/SOURCE.md
  GridGeometry g;
  g.size = Eigen::Vector3i(100, 120, 40);
  g.origin = Eigen::Vector3d(-120.5, 80.25, -300);
  g.spacing = Eigen::Vector3d(0.8, 0.8, 2.5);
  g.direction << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  return g;
}

MarkerSet readFile(const std::string& path, MarkerKind kind = MarkerKind::Landmark) {
  const std::string text = readTextFile(path), ext = fileExtension(path);
  if (ext == ".mrk.json") return parseSlicerMarkups(text, path, kind);
  if (ext == ".fcsv") return parseFcsv(text, path, kind);
  if (ext == ".csv") return parseMarkerCsv(text, path, kind);
  const GridGeometry scan = annotScan();
  return parseItkSnapAnnotations(text, path, scan, kind);
}

// ---- Slicer's own files ----

TEST(SlicerFiles, Slicer3FiducialList) {
  const MarkerSet set = readFile(kSlicer + "slicer3.fcsv");
  EXPECT_EQ(set.name, "midsag");
  ASSERT_EQ(set.markers.size(), 56u);
  EXPECT_EQ(set.countDefined(), 56u);
  EXPECT_EQ(set.markers.front().label, "midsag2");
  expectAt(set.markers.front().position, -12.5, 93.5, 7.5);  // RAS 12.5,-93.5,7.5
  EXPECT_EQ(set.markers.back().label, "midsag57");
  expectAt(set.markers.back().position, 11.5, -71.5, -26.5);
  for (const Marker& m : set.markers) {
    EXPECT_TRUE(m.selected && m.visible) << m.label;
    EXPECT_TRUE(m.id.empty()) << m.label;
  }
}

TEST(SlicerFiles, Slicer44WithIdsAndAssociatedNodes) {
  const MarkerSet set = readFile(kSlicer + "L1.fcsv");
  ASSERT_EQ(set.markers.size(), 2u);
  EXPECT_EQ(set.markers[0].id, "vtkMRMLMarkupsFiducialNode_0");
  EXPECT_EQ(set.markers[1].id, "vtkMRMLMarkupsFiducialNode_1");
  EXPECT_EQ(set.markers[0].label, "L1-P1");
  EXPECT_EQ(set.markers[0].associatedNodeID, "vtkMRMLDiffusionTensorVolumeNode1");
  expectAt(set.markers[0].position, -43.3769, -23.1343, 0.0);  // CoordinateSystem = 0: RAS
  expectAt(set.markers[1].position, -49.8834, 4.33769, 0.0);
}

void expectSlicer54Points(const MarkerSet& set) {
  ASSERT_EQ(set.markers.size(), 3u);
  const char* labels[] = {"crossed", "locked", "editing"};
  const MarkerStatus statuses[] = {MarkerStatus::Missing, MarkerStatus::Defined, MarkerStatus::Undefined};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(set.markers[i].label, labels[i]);
    EXPECT_EQ(set.markers[i].status, statuses[i]) << labels[i];
    EXPECT_EQ(set.markers[i].id, std::to_string(i + 1));
    EXPECT_EQ(set.markers[i].locked, i == 1);
  }
  expectAt(set.markers[1].position, -517.4872665534805, -5.684341886080802e-14, 122.92020373514431);
}

TEST(SlicerFiles, Slicer54MissingAndUndefinedInBothFormats) {
  const MarkerSet json = readFile(kSlicer + "slicer5.4_missing.mrk.json"),
                  fcsv = readFile(kSlicer + "slicer5.4_missing.fcsv");
  expectSlicer54Points(json);
  expectSlicer54Points(fcsv);
  EXPECT_EQ(json.countDefined(), 1u);
}

TEST(SlicerFiles, MarkupsTableExportedBySlicer) {
  const MarkerSet all = readFile(kSlicer + "slicer_table_all_fields.csv");
  ASSERT_EQ(all.markers.size(), 3u);
  EXPECT_EQ(all.countDefined(), 3u);
  expectAt(all.markers[1].position, 32.809, 33.7369, -10.2143);  // RAS -32.809,-33.7369
  EXPECT_FALSE(all.markers[0].locked);

  // Quoted as vtkDelimitedTextWriter quotes; an undefined row keeps the zeros Slicer writes.
  const MarkerSet table = readFile(kMarkers + "slicer_table_lps_undefined.csv", MarkerKind::IcpMarker);
  ASSERT_EQ(table.markers.size(), 3u);
  EXPECT_EQ(table.markers[0].label, "apex, left");
  expectAt(table.markers[0].position, -10.5, 20.25, 30.0);
  EXPECT_EQ(table.markers[0].description, "first");
  EXPECT_EQ(table.markers[1].status, MarkerStatus::Undefined);  // defined = 0: not a point at 0,0,0
  EXPECT_EQ(table.markers[2].status, MarkerStatus::Defined);
  EXPECT_FALSE(table.markers[2].selected);
  EXPECT_FALSE(table.markers[2].visible);
  EXPECT_TRUE(table.markers[2].locked);
  EXPECT_EQ(table.markers[2].description, "third, last");
  EXPECT_EQ(table.count(MarkerKind::IcpMarker), 3u);
}

TEST(ItkSnapFiles, ColourAndTags) {
  const MarkerSet set = readFile(kMarkers + "itksnap4_color_tags.annot");
  ASSERT_EQ(set.markers.size(), 2u);
  ASSERT_TRUE(set.markers[0].color.has_value());
  EXPECT_EQ(*set.markers[0].color, Eigen::Vector3d(0, 0.5, 1));
  EXPECT_EQ(set.markers[0].tags, (std::vector<std::string>{"liver", "reviewed"}));
  EXPECT_TRUE(set.markers[1].tags.empty());
  expectAt(set.markers[1].position, -120.5, 80.25, -300.0);
}

// ---- What Slicer writes, and what it reads ----

TEST(SlicerMarkupsWriter, ControlPointsAsSlicer54WroteThem) {
  const std::string path = kSlicer + "slicer5.4_missing.mrk.json";
  const OrderedJson theirs = OrderedJson::parse(readTextFile(path));
  const OrderedJson ours = OrderedJson::parse(formatSlicerMarkups(readFile(path)));
  ASSERT_EQ(ours["markups"].size(), 1u);
  // Same members in the same order with the same values, "position": "" for the missing and the
  // undefined point.
  EXPECT_EQ(ours["markups"][0]["controlPoints"], theirs["markups"][0]["controlPoints"])
      << ours["markups"][0]["controlPoints"].dump(1);
  EXPECT_EQ(ours["@schema"], theirs["@schema"]);
  for (const char* key : {"type", "coordinateSystem", "coordinateUnits", "locked", "fixedNumberOfControlPoints",
                          "labelFormat", "lastUsedControlPointNumber"})
    EXPECT_EQ(ours["markups"][0][key], theirs["markups"][0][key]) << key;
}

TEST(SlicerMarkupsWriter, EveryStatusWritesSlicersPositionForm) {
  MarkerSet set;
  for (MarkerStatus s : {MarkerStatus::Defined, MarkerStatus::Undefined, MarkerStatus::Preview, MarkerStatus::Missing}) {
    Marker m;
    m.label = markerStatusName(s);
    m.status = s;
    m.position = Eigen::Vector3d(1, 2, 3);
    set.markers.push_back(m);
  }
  const OrderedJson doc = OrderedJson::parse(formatSlicerMarkups(set));
  const OrderedJson& points = doc["markups"][0]["controlPoints"];
  ASSERT_EQ(points.size(), 4u);
  EXPECT_TRUE(points[0]["position"].is_array());
  EXPECT_EQ(points[1]["position"], "");
  EXPECT_TRUE(points[2]["position"].is_array());  // a suggestion keeps its proposed position
  EXPECT_EQ(points[3]["position"], "");
  EXPECT_EQ(points[3]["positionStatus"], "missing");
  const std::string fcsv = formatFcsv(set);
  EXPECT_NE(fcsv.find(",missing,,,3,0\n"), std::string::npos) << fcsv;
  EXPECT_NE(fcsv.find("\n4,0,0,0,"), std::string::npos) << fcsv;  // no position: zeros, as the status says
}

// ---- Our .mrk.json against Slicer's published schema ----

test::JsonSchemaSubset slicerSchema() {
  return test::JsonSchemaSubset(nlohmann::json::parse(readTextFile(kSlicer + "markups-schema-v1.0.3.json")));
}

std::string describe(const std::vector<test::SchemaViolation>& violations) {
  std::string out;
  for (const auto& v : violations) out += "  " + v.path + ": " + v.problem + "\n";
  return out;
}

// Markers of every kind and every extra we write: template positions, colours, tags, ids, a name.
MarkerSet placedSet() {
  MarkerSet set;
  set.name = "liver";
  for (int i = 0; i < 6; ++i) {
    Marker m;
    m.label = "p" + std::to_string(i);
    m.kind = MarkerKind(i % 3);
    m.status = i == 4 ? MarkerStatus::Preview : MarkerStatus::Defined;
    m.position = Eigen::Vector3d(0.1 * i, -20.5 + i, 1e3 / (i + 1));
    if (i % 2 == 0) m.templatePosition = Eigen::Vector3d(i, 2.0 * i, -1.0);
    if (i == 1) m.color = Eigen::Vector3d(0, 0.5, 1);
    if (i == 1) m.tags = {"liver", "reviewed"};
    if (i == 2) m.id = "vtkMRMLMarkupsFiducialNode_7";
    if (i == 3) m.associatedNodeID = "vtkMRMLScalarVolumeNode1";
    m.description = i == 5 ? "with \"quotes\", commas" : "";
    set.markers.push_back(m);
  }
  return set;
}

TEST(SlicerSchema, PlacedPointsValidate) {
  const auto schema = slicerSchema();
  const MarkerSet set = placedSet();
  const std::string text = formatSlicerMarkups(set);
  const auto violations = schema.validate(nlohmann::json::parse(text));
  std::cout << "placed points: " << violations.size() << " schema violations\n" << describe(violations);
  EXPECT_TRUE(violations.empty());
  MarkerSet empty;
  EXPECT_TRUE(schema.validate(nlohmann::json::parse(formatSlicerMarkups(empty))).empty());
}

// Slicer 5 writes "position": "" and positionStatus "missing" under schema v1.0.3, which lists neither
// (the schema's position is an array of 3 numbers, its status enum undefined/preview/defined). We write
// what Slicer writes, so those two members, and nothing else, depart from the published schema, in our
// documents exactly as in Slicer's own.
void expectOnlySlicersDepartures(const std::vector<test::SchemaViolation>& violations, std::size_t unplaced,
                                 std::size_t missing) {
  std::size_t positions = 0, statuses = 0;
  for (const auto& v : violations) {
    const bool position = v.path.size() > 9 && v.path.compare(v.path.size() - 9, 9, "/position") == 0 &&
                          v.problem == "expected \"array\", found string";
    const bool status = v.path.size() > 15 && v.path.compare(v.path.size() - 15, 15, "/positionStatus") == 0 &&
                        v.problem.rfind("\"missing\" is not one of", 0) == 0;
    positions += position;
    statuses += status;
    EXPECT_TRUE(position || status) << v.path << ": " << v.problem;
  }
  EXPECT_EQ(positions, unplaced);
  EXPECT_EQ(statuses, missing);
}

TEST(SlicerSchema, UnplacedAndMissingPointsDepartOnlyWhereSlicerDoes) {
  const auto schema = slicerSchema();
  MarkerSet set = placedSet();
  set.markers[0].status = MarkerStatus::Undefined;
  set.markers[3].status = MarkerStatus::Missing;
  set.markers[5].status = MarkerStatus::Missing;
  const auto ours = schema.validate(nlohmann::json::parse(formatSlicerMarkups(set)));
  std::cout << "3 unplaced points (1 undefined, 2 missing): " << ours.size() << " departures\n" << describe(ours);
  expectOnlySlicersDepartures(ours, 3, 2);

  const auto theirs = schema.validate(nlohmann::json::parse(readTextFile(kSlicer + "slicer5.4_missing.mrk.json")));
  std::cout << "Slicer 5.4's own file: " << theirs.size() << " departures\n" << describe(theirs);
  expectOnlySlicersDepartures(theirs, 2, 1);
}

TEST(SlicerSchema, BrokenDocumentsDoNotValidate) {
  const auto schema = slicerSchema();
  const nlohmann::json good = nlohmann::json::parse(formatSlicerMarkups(placedSet()));
  ASSERT_TRUE(schema.validate(good).empty());
  struct Breakage {
    const char* what;
    std::function<void(nlohmann::json&)> apply;
    const char* path;
  };
  const Breakage breakages[] = {
      {"no markups", [](nlohmann::json& d) { d.erase("markups"); }, "/"},
      {"misspelt type", [](nlohmann::json& d) { d["markups"][0]["type"] = "Fidicial"; }, "/markups/0/type"},
      {"2-number position",
       [](nlohmann::json& d) { d["markups"][0]["controlPoints"][0]["position"] = {1.0, 2.0}; },
       "/markups/0/controlPoints/0/position"},
      {"string flag", [](nlohmann::json& d) { d["markups"][1]["controlPoints"][0]["selected"] = "yes"; },
       "/markups/1/controlPoints/0/selected"},
      {"numeric id", [](nlohmann::json& d) { d["markups"][0]["controlPoints"][1]["id"] = 2; },
       "/markups/0/controlPoints/1/id"},
      {"coordinate system", [](nlohmann::json& d) { d["markups"][2]["coordinateSystem"] = "IJK"; },
       "/markups/2/coordinateSystem"},
      {"8-number orientation",
       [](nlohmann::json& d) { d["markups"][0]["controlPoints"][0]["orientation"].erase(0); },
       "/markups/0/controlPoints/0/orientation"},
  };
  for (const Breakage& b : breakages) {
    nlohmann::json doc = good;
    b.apply(doc);
    const auto violations = schema.validate(doc);
    ASSERT_FALSE(violations.empty()) << b.what;
    EXPECT_EQ(violations.front().path, b.path) << b.what << "\n" << describe(violations);
  }
  EXPECT_THROW(test::JsonSchemaSubset(nlohmann::json::parse(R"({"oneOf": []})")), std::invalid_argument);
}

// ---- Round trips ----

// What a format keeps of a marker, compared field by field.
struct Keeps {
  bool kind, flags, description, id, templatePosition, colorAndTags, unplaced, associatedNode;
  bool redWithoutColor = false;  // ITK-SNAP: every annotation has a colour, red by default
  bool voxelPositions = false;   // through voxel coordinates: equal to round-off
  bool groupsByKind = false;     // one markup per kind: landmarks, then icp, then attachments
};

MarkerSet groupedByKind(MarkerSet set) {
  std::stable_sort(set.markers.begin(), set.markers.end(),
                   [](const Marker& a, const Marker& b) { return int(a.kind) < int(b.kind); });
  return set;
}

void expectSameMarkers(const MarkerSet& original, const MarkerSet& b, const Keeps& keeps, const std::string& what) {
  const MarkerSet a = keeps.groupsByKind ? groupedByKind(original) : original;
  ASSERT_EQ(a.markers.size(), b.markers.size()) << what;
  for (std::size_t i = 0; i < a.markers.size(); ++i) {
    const Marker &x = a.markers[i], &y = b.markers[i];
    SCOPED_TRACE(what + ", marker " + std::to_string(i + 1) + " '" + x.label + "'");
    EXPECT_EQ(x.label, y.label);
    EXPECT_EQ(x.status, y.status);
    if (hasPosition(x.status) && keeps.voxelPositions) {
      EXPECT_LT((x.position - y.position).norm(), 1e-9);
    } else if (hasPosition(x.status)) {
      EXPECT_EQ(x.position, y.position);  // exact: shortest round-trip digits
    }
    if (keeps.kind) {
      EXPECT_EQ(x.kind, y.kind);
    }
    if (keeps.flags) {
      EXPECT_EQ(std::make_tuple(x.selected, x.locked, x.visible), std::make_tuple(y.selected, y.locked, y.visible));
    }
    if (keeps.description) {
      EXPECT_EQ(x.description, y.description);
    }
    if (keeps.id && !x.id.empty()) {
      EXPECT_EQ(x.id, y.id);
    }
    if (keeps.associatedNode) {
      EXPECT_EQ(x.associatedNodeID, y.associatedNodeID);
    }
    if (keeps.templatePosition) {
      EXPECT_EQ(x.templatePosition, y.templatePosition);
    }
    if (keeps.colorAndTags) {
      EXPECT_EQ(keeps.redWithoutColor ? x.color.value_or(Eigen::Vector3d(1, 0, 0)) : x.color, y.color);
      EXPECT_EQ(x.tags, y.tags);
    }
  }
}

struct Format {
  const char* extension;
  Keeps keeps;
  std::function<std::string(const MarkerSet&)> write;
  std::function<MarkerSet(const std::string&)> read;
};

std::vector<Format> formats() {
  const GridGeometry scan = annotScan();
  return {
      {".mrk.json", {true, true, true, true, true, true, true, true, false, false, true}, formatSlicerMarkups,
       [](const std::string& t) { return parseSlicerMarkups(t, "round.mrk.json", MarkerKind::Landmark); }},
      {".fcsv", {false, true, true, true, false, false, true, true}, formatFcsv,
       [](const std::string& t) { return parseFcsv(t, "round.fcsv", MarkerKind::Landmark); }},
      {".csv", {true, true, true, true, false, true, true, true}, formatMarkerCsv,
       [](const std::string& t) { return parseMarkerCsv(t, "round.csv", MarkerKind::Landmark); }},
      {".annot", {false, false, false, false, false, true, false, false, true, true},
       [scan](const MarkerSet& s) { return formatItkSnapAnnotations(s, scan); },
       [scan](const std::string& t) { return parseItkSnapAnnotations(t, "round.annot", scan, MarkerKind::Landmark); }},
  };
}

// Every file, through every format that can hold it: read theirs, write ours, read ours back (the
// same markers), write again (the same text).
TEST(RoundTrip, TheirFilesThroughEveryFormat) {
  const std::string files[] = {kSlicer + "slicer3.fcsv",        kSlicer + "L1.fcsv",
                               kSlicer + "slicer5.4_missing.fcsv", kSlicer + "slicer5.4_missing.mrk.json",
                               kSlicer + "slicer_table_all_fields.csv", kMarkers + "slicer_table_lps_undefined.csv",
                               kMarkers + "itksnap4_color_tags.annot", kMarkers + "slicer_v1.0.3_lps.mrk.json"};
  int trips = 0;
  for (const std::string& file : files) {
    const MarkerSet theirs = readFile(file);
    for (const Format& f : formats()) {
      if (std::string(f.extension) == ".annot" && theirs.countDefined() != theirs.markers.size()) {
        EXPECT_THROW(f.write(theirs), UsageError) << file;  // .annot holds only placed landmarks
        continue;
      }
      const std::string text = f.write(theirs);
      const MarkerSet ours = f.read(text);
      expectSameMarkers(theirs, ours, f.keeps, file + " -> " + f.extension);
      EXPECT_EQ(f.write(ours), text) << file << " -> " << f.extension;
      ++trips;
    }
  }
  std::cout << trips << " round trips of " << std::size(files) << " files\n";
}

// Ours -> Slicer's form -> ours: our markers written in each format and read back give the same markers,
// and a second write the same text; .mrk.json keeps everything.
TEST(RoundTrip, OurMarkersThroughEveryFormat) {
  MarkerSet set = placedSet();
  set.markers[0].status = MarkerStatus::Undefined;
  set.markers[3].status = MarkerStatus::Missing;
  for (const Format& f : formats()) {
    if (std::string(f.extension) == ".annot") continue;  // unplaced markers: covered above
    const std::string text = f.write(set);
    const MarkerSet back = f.read(text);
    expectSameMarkers(set, back, f.keeps, std::string("ours -> ") + f.extension);
    EXPECT_EQ(f.write(back), text) << f.extension;
  }
  const MarkerSet json = parseSlicerMarkups(formatSlicerMarkups(set), "round.mrk.json", MarkerKind::Landmark);
  EXPECT_EQ(json.name, "liver");
}

TEST(RoundTrip, AnnotColoursAndTagsThroughMrkJson) {
  const GridGeometry scan = annotScan();
  const MarkerSet annot = readFile(kMarkers + "itksnap4_color_tags.annot");
  const MarkerSet viaJson =
      parseSlicerMarkups(formatSlicerMarkups(annot), "via.mrk.json", MarkerKind::Landmark);
  EXPECT_EQ(formatItkSnapAnnotations(viaJson, scan), formatItkSnapAnnotations(annot, scan));
  EXPECT_EQ(viaJson.markers[0].tags, (std::vector<std::string>{"liver", "reviewed"}));
  MarkerSet spaced = annot;
  spaced.markers[0].tags = {"two words"};
  EXPECT_THROW(formatItkSnapAnnotations(spaced, scan), UsageError);  // ITK-SNAP would keep "two"
}

// ---- Names and ids ----

TEST(MarkupNames, CarryTheSetNameAndTheKind) {
  auto markupNames = [](const MarkerSet& s) {
    std::vector<std::string> names;
    const OrderedJson doc = OrderedJson::parse(formatSlicerMarkups(s));
    for (const auto& m : doc["markups"]) names.push_back(m["name"]);
    return names;
  };
  MarkerSet set;
  set.markers.resize(2);
  EXPECT_EQ(markupNames(set), std::vector<std::string>{"landmarks"});
  set.name = "F";
  EXPECT_EQ(markupNames(set), std::vector<std::string>{"F"});  // a Slicer point list keeps its name
  set.markers[1].kind = MarkerKind::IcpMarker;
  EXPECT_EQ(markupNames(set), (std::vector<std::string>{"F (landmarks)", "F (icp)"}));
  for (MarkerKind defaultKind : {MarkerKind::Landmark, MarkerKind::IcpMarker, MarkerKind::Attachment}) {
    const MarkerSet back = parseSlicerMarkups(formatSlicerMarkups(set), "names.mrk.json", defaultKind);
    EXPECT_EQ(back.name, "F");
    EXPECT_EQ(back.markers[0].kind, MarkerKind::Landmark);
    EXPECT_EQ(back.markers[1].kind, MarkerKind::IcpMarker);
  }
}

TEST(ControlPointIds, KeptUniqueAndFilledIn) {
  MarkerSet set;
  set.markers.resize(4);
  set.markers[0].id = "2";
  set.markers[2].id = "2";  // a duplicate gets a fresh id
  set.markers[3].id = "vtkMRMLMarkupsFiducialNode_3";
  const MarkerSet back = parseFcsv(formatFcsv(set), "ids.fcsv", MarkerKind::Landmark);
  const MarkerSet json = parseSlicerMarkups(formatSlicerMarkups(set), "ids.mrk.json", MarkerKind::Landmark);
  for (const MarkerSet* s : {&back, &json}) {
    ASSERT_EQ(s->markers.size(), 4u);
    EXPECT_EQ(s->markers[0].id, "2");
    EXPECT_EQ(s->markers[1].id, "1");
    EXPECT_EQ(s->markers[2].id, "3");
    EXPECT_EQ(s->markers[3].id, "vtkMRMLMarkupsFiducialNode_3");
  }
}

// ---- Refusals ----

TEST(BadMarkers, UnclosedQuoteNamesFileAndRow) {
  test::expectOneLineBadInput(kBad + "markers_unclosed_quote.fcsv", "line 4: field 12 opens a quote", [] {
    readFile(kBad + "markers_unclosed_quote.fcsv");
  });
  test::expectOneLineBadInput("inline.csv", "line 2: field 1 opens a quote", [] {
    parseMarkerCsv("label,l,p,s\n\"apex,1,2,3\n", "inline.csv", MarkerKind::Landmark);
  });
  test::expectOneLineBadInput(kBad + "markers_slicer3_long_row.fcsv", "line 3: a Slicer 3 row", [] {
    readFile(kBad + "markers_slicer3_long_row.fcsv");
  });
  test::expectOneLineBadInput("status.fcsv", "line 2: position status must be", [] {
    parseFcsv("# Markups fiducial file version = 5.4\n1,1,2,3,0,0,0,1,1,1,0,a,,,4,0\n", "status.fcsv",
              MarkerKind::Landmark);
  });
}

}  // namespace
}  // namespace vesalius::io
