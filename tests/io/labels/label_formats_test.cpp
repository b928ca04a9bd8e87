// Label tables as 3D Slicer and ITK-SNAP write them (their own test and resource files, testdata/slicer and
// testdata/itksnap), and ours written in their formats read back unchanged.
#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/label_table_io.h"
#include "vesalius/io/text_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;
using Rgb = std::array<std::uint8_t, 3>;

const std::string kData = VESALIUS_TESTDATA;

void expectEntry(const LabelTable& table, Label id, const std::string& name, Rgb color) {
  const LabelEntry* entry = table.find(id);
  ASSERT_NE(entry, nullptr) << "no label " << id;
  EXPECT_EQ(entry->name, name) << "label " << id;
  EXPECT_EQ(entry->color, color) << "label " << id;
}

// The data lines of a file as the file itself counts them (not comments, not blank, not id 0).
std::size_t dataLines(const std::string& path, bool header) {
  std::ifstream in(path);
  std::size_t count = 0;
  bool seenHeader = !header;
  for (std::string line; std::getline(in, line);) {
    const std::string_view text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    if (!seenHeader) {
      seenHeader = true;
      continue;
    }
    if (splitWhitespace(text).front() == "0" || text.rfind("0,", 0) == 0) continue;
    ++count;
  }
  return count;
}

TEST(LabelFormats, ReadsSlicerCtbl) {
  const std::string path = kData + "/slicer/ColorTest.ctbl";
  const LabelTable table = readLabelTable(path);
  EXPECT_EQ(table.entries.size(), 2u);  // "# 3 values", id 0 is the background
  expectEntry(table, 1, "one", {{255, 59, 21}});
  expectEntry(table, 2, "two", {{41, 84, 255}});
  EXPECT_EQ(table.find(0), nullptr);
}

TEST(LabelFormats, ReadsSlicerColourFile) {
  const std::string path = kData + "/slicer/AbdomenColors.txt";
  const LabelTable table = readLabelTable(path);
  std::cout << path << ": " << table.entries.size() << " labels\n";
  EXPECT_EQ(table.entries.size(), dataLines(path, false));
  EXPECT_EQ(table.entries.size(), 91u);
  expectEntry(table, 2, "bone", {{255, 255, 255}});
  expectEntry(table, 8, "inferior_vena_cava", {{50, 21, 255}});
  expectEntry(table, 12, "portal_vein_and_superior_mesenteric_vein", {{41, 166, 255}});
  EXPECT_EQ(table.resolve("liver"), 3);
}

TEST(LabelFormats, ReadsSlicerCsvColourTables) {
  struct Case {
    std::string file;
    std::size_t count;
    Label id;
    std::string name;
    Rgb color;
  };
  for (const Case& c : {Case{"ColorTest.csv", 3, 5, "five", {{255, 59, 21}}},
                        Case{"ColorTestMissingAlpha.csv", 3, 10, "ten", {{41, 84, 255}}},
                        Case{"ColorTestWithTerminology.csv", 4, 6, "right_kidney_mass", {{20, 28, 140}}}}) {
    const std::string path = kData + "/slicer/" + c.file;
    EXPECT_TRUE(isLabelTableFile(path)) << c.file;
    const LabelTable table = readLabelTable(path);
    std::cout << c.file << ": " << table.entries.size() << " labels\n";
    EXPECT_EQ(table.entries.size(), c.count) << c.file;
    EXPECT_EQ(table.entries.size(), dataLines(path, true)) << c.file;
    expectEntry(table, c.id, c.name, c.color);
  }
  expectEntry(readLabelTable(kData + "/slicer/ColorTest.csv"), 1, "one", {{10, 200, 40}});
  expectEntry(readLabelTable(kData + "/slicer/ColorTestWithTerminology.csv"), 10, "catheter_renal_artery",
              {{220, 19, 37}});
}

TEST(LabelFormats, AMarkerCsvIsNotALabelTable) {
  EXPECT_FALSE(isLabelTableFile(kData + "/markers/markers_ras.csv"));
  EXPECT_TRUE(isLabelTableFile(kData + "/itksnap/MRIcrop-seg.label"));
}

TEST(LabelFormats, ReadsItkSnapLabelDescriptions) {
  const std::string path = kData + "/itksnap/MRIcrop-seg.label";
  const LabelTable table = readLabelTable(path);
  std::cout << path << ": " << table.entries.size() << " labels\n";
  EXPECT_EQ(table.entries.size(), dataLines(path, false));
  EXPECT_EQ(table.entries.size(), 11u);  // ids 1..11; 0 is "Clear"
  expectEntry(table, 1, "vent-lat", {{0, 30, 255}});
  expectEntry(table, 8, "corpus-callosum", {{255, 8, 186}});
  expectEntry(table, 11, "arteries", {{4, 0, 128}});
  EXPECT_EQ(table.find(0), nullptr);
}

TEST(LabelFormats, ItkSnapNamesKeepSpacesAndEmptyOnesAreNamed) {
  const LabelTable table = parseLabelTable(
      "# ITK-SnAP Label Description File\n    0     0    0    0        0  0  0    \"Clear Label\"\n"
      "    3   230  220   70     0.5  1  0    \"subcutaneous fat\"\n  300  1 2 3  1.00  0  1  \"\"\n",
      "spaces.txt");
  expectEntry(table, 3, "subcutaneous fat", {{230, 220, 70}});
  expectEntry(table, 300, "label_300", {{1, 2, 3}});
}

TEST(LabelFormats, RefusesMalformedItkSnapLines) {
  for (const std::string line : {"1 255 0 0 1.5 1 1 \"alpha above one\"", "1 255 0 0 1 1 \"seven fields\"",
                                 "1 255 0 0 1 1 1 \"not closed", "1 255 0 0 1 2 1 \"visibility two\"",
                                 "1 255 0 0 1 1 1 \"a\" trailing"}) {
    try {
      parseLabelTable(line + "\n", "bad.label");
      ADD_FAILURE() << "accepted: " << line;
    } catch (const BadInput& error) {
      std::cout << error.what() << '\n';
      EXPECT_EQ(std::string(error.what()).rfind("bad.label: line 1", 0), 0u) << error.what();
    }
  }
}

// A table of ours: ids above 255, names with underscores and digits, colours at the ends of the range.
LabelTable ourTable() {
  LabelTable table;
  table.add({1, "skin", {{255, 0, 0}}});
  table.add({2, "subcutaneous_fat", {{230, 220, 70}}});
  table.add({5, "soft_tissue", {{0, 0, 0}}});
  table.add({88, "femur_left", {{255, 255, 255}}});
  table.add({300, "vertebrae_L5", {{12, 34, 56}}});
  table.add({65535, "last", {{1, 2, 3}}});
  return table;
}

void expectSameTable(const LabelTable& a, const LabelTable& b, const std::string& what) {
  ASSERT_EQ(a.entries.size(), b.entries.size()) << what;
  for (std::size_t k = 0; k < a.entries.size(); ++k) {
    EXPECT_EQ(a.entries[k].id, b.entries[k].id) << what;
    EXPECT_EQ(a.entries[k].name, b.entries[k].name) << what;
    EXPECT_EQ(a.entries[k].color, b.entries[k].color) << what << ", label " << a.entries[k].id;
  }
}

// Ours -> theirs -> ours, for our own table and for each of theirs once read.
TEST(LabelFormats, RoundTripsThroughSlicerAndItkSnapFormats) {
  std::vector<std::pair<std::string, LabelTable>> inputs{{"ours", ourTable()}};
  for (const std::string file : {"slicer/AbdomenColors.txt", "slicer/ColorTestWithTerminology.csv",
                                 "itksnap/MRIcrop-seg.label", "slicer/ColorTest.ctbl"})
    inputs.emplace_back(file, readLabelTable(kData + "/" + file));
  for (const auto& [what, table] : inputs) {
    expectSameTable(table, parseLabelTable(formatSlicerColorTable(table), "t.ctbl"), what + " via .ctbl");
    expectSameTable(table, parseLabelTable(formatItkSnapLabels(table), "t.label.txt"), what + " via ITK-SNAP");
    expectSameTable(table, parseLabelTable(formatLabelTable(table), "t.tsv"), what + " via .tsv");
  }
}

TEST(LabelFormats, WrittenTablesFollowTheirProgramsLayout) {
  const LabelTable table = ourTable();
  const std::string ctbl = formatSlicerColorTable(table);
  EXPECT_NE(ctbl.find("\n2 subcutaneous_fat 230 220 70 255\n"), std::string::npos) << ctbl;  // opaque
  const std::string snap = formatItkSnapLabels(table);
  // ITK-SNAP's ColorLabelTable::ValidateFile checks the second line.
  EXPECT_EQ(snap.substr(snap.find('\n') + 1, 33), "# ITK-SnAP Label Description File");
  EXPECT_NE(snap.find("\"subcutaneous_fat\"\n"), std::string::npos) << snap;
  // A name with a space cannot be one ctbl token: Slicer's own convention writes '_' for it.
  LabelTable spaced;
  spaced.add({3, "subcutaneous fat", {{1, 2, 3}}});
  EXPECT_EQ(parseLabelTable(formatSlicerColorTable(spaced), "s.ctbl").find(3)->name, "subcutaneous_fat");
  EXPECT_EQ(parseLabelTable(formatItkSnapLabels(spaced), "s.txt").find(3)->name, "subcutaneous fat");
  // ITK-SNAP reads a name up to the next quote: a quote in a name becomes an apostrophe. A Slicer name may
  // hold a quote, and such a line is still read as Slicer's.
  LabelTable quoted;
  quoted.add({4, "a \"quoted\" name", {{1, 2, 3}}});
  EXPECT_EQ(parseLabelTable(formatItkSnapLabels(quoted), "q.txt").find(4)->name, "a 'quoted' name");
  EXPECT_EQ(parseLabelTable(formatSlicerColorTable(quoted), "q.ctbl").find(4)->name, "a_\"quoted\"_name");
}

// writeLabelMap puts all three tables beside the map, and readLabelMap finds each of them alone.
TEST(LabelFormats, LabelMapsCarryAllThreeTables) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / "three-tables";
  fs::remove_all(folder);
  fs::create_directories(folder);
  GridGeometry geometry;
  geometry.size = {4, 3, 2};
  LabelMap map{Grid<Label>(geometry, 0), ourTable()};
  const std::vector<Label> ids{1, 2, 5, 88, 300, 65535};
  for (std::size_t n = 0; n < ids.size(); ++n) map.labels.values[n * 4] = ids[n];
  const std::string path = (folder / "labels.nii.gz").string();
  writeLabelMap(path, map);
  const std::vector<std::string> tables = labelTableSidecarPaths(path);
  ASSERT_EQ(tables.size(), 3u);
  EXPECT_EQ(tables[1], (folder / "labels.ctbl").string());
  EXPECT_EQ(tables[2], (folder / "labels.label.txt").string());
  for (const std::string& table : tables) expectSameTable(map.table, readLabelTable(table), table);
  // Each alone beside the map names the labels.
  for (std::size_t keep = 0; keep < tables.size(); ++keep) {
    const fs::path copy = folder / ("alone" + std::to_string(keep));
    fs::create_directories(copy);
    fs::copy_file(path, copy / "labels.nii.gz");
    fs::copy_file(tables[keep], copy / fs::path(tables[keep]).filename());
    const LabelMap back = readLabelMap((copy / "labels.nii.gz").string());
    expectSameTable(map.table, back.table, "beside: " + tables[keep]);
    EXPECT_EQ(back.labels.values, map.labels.values);
  }
  // An existing Slicer table beside the output is not replaced without force, and nothing is written.
  const std::string second = (folder / "second.nii.gz").string();
  { std::ofstream(folder / "second.ctbl") << "1 kept 1 2 3 255\n"; }
  EXPECT_THROW(writeLabelMap(second, map), UsageError);
  EXPECT_FALSE(fs::exists(second));
  EXPECT_FALSE(fs::exists(folder / "second.tsv"));
  EXPECT_EQ(readLabelTable((folder / "second.ctbl").string()).find(1)->name, "kept");
}

// A marker CSV beside a label map is not taken for its table; a Slicer colour CSV is.
TEST(LabelFormats, CsvBesideALabelMapIsReadOnlyIfItIsAColourTable) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / "csv-beside";
  fs::remove_all(folder);
  fs::create_directories(folder);
  GridGeometry geometry;
  geometry.size = {3, 3, 3};
  LabelMap map{Grid<Label>(geometry, 0), {}};
  map.labels.values[0] = 5;
  map.labels.values[1] = 10;
  const std::string path = (folder / "seg.nii.gz").string();
  writeLabelMap(path, map);
  for (const std::string& table : labelTableSidecarPaths(path)) fs::remove(table);
  fs::copy_file(kData + "/markers/markers_ras.csv", folder / "seg.csv");
  EXPECT_EQ(readLabelMap(path).table.find(5)->name, "label_5");
  fs::remove(folder / "seg.csv");
  fs::copy_file(kData + "/slicer/ColorTest.csv", folder / "seg.csv");
  const LabelMap back = readLabelMap(path);
  expectEntry(back.table, 5, "five", {{255, 59, 21}});
  expectEntry(back.table, 10, "ten", {{41, 84, 255}});
}

}  // namespace
}  // namespace vesalius::io
