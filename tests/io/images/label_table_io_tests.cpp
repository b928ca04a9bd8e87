// Label tables in memory and on disk: TSV with and without colours, 3D Slicer colour tables, errors.
#include "vesalius/io/label_table_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

TEST(LabelTableIo, ReadsTotalSegmentatorTsvWithDefaultColours) {
  const LabelTable table = parseLabelTable("label\tname\n1\tspleen\n5\tliver\n88\tfemur_left\n", "total.tsv");
  ASSERT_EQ(table.entries.size(), 3u);
  ASSERT_NE(table.find(5), nullptr);
  EXPECT_EQ(table.find(5)->name, "liver");
  EXPECT_EQ(table.find(88)->color, defaultLabelColor(88));
}

TEST(LabelTableIo, ReadsOwnTsvWithColoursAndSpacesInNames) {
  const LabelTable table = parseLabelTable(
      "label\tname\tr\tg\tb\r\n0\tbackground\t0\t0\t0\r\n"
      "3\tsubcutaneous fat\t230\t220\t70\r\n",
      "own.tsv");
  ASSERT_EQ(table.entries.size(), 1u);  // id 0 is the background, not listed
  EXPECT_EQ(table.entries[0].id, 3);
  EXPECT_EQ(table.entries[0].name, "subcutaneous fat");
  EXPECT_EQ(table.entries[0].color, (std::array<std::uint8_t, 3>{{230, 220, 70}}));
}

TEST(LabelTableIo, ReadsSlicerColourTable) {
  const LabelTable table = parseLabelTable(
      "# Color table file GenericAnatomyColors.ctbl\n# 3 values\n"
      "0 Background 0 0 0 0\n1 tissue 128 174 128 255\n"
      "\n7 liver 221 130 101 255\n12 spleen\n",
      "colors.ctbl");
  ASSERT_EQ(table.entries.size(), 3u);
  EXPECT_EQ(table.find("LIVER")->id, 7);
  EXPECT_EQ(table.find(1)->color, (std::array<std::uint8_t, 3>{{128, 174, 128}}));
  EXPECT_EQ(table.find(12)->color, defaultLabelColor(12));
}

void expectBadLine(const std::string& text, const std::string& fragment) {
  try {
    parseLabelTable(text, "table.tsv");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const BadInput& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("table.tsv: line ", 0), 0u) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

TEST(LabelTableIo, RejectsMalformedLinesNamingTheLine) {
  expectBadLine("label\tname\n5\tliver\n5\tspleen\n", "listed twice");
  expectBadLine("label\tname\n70000\tbig\n", "outside 0..65535");
  expectBadLine("label\tname\tr\tg\tb\n5\tliver\t300\t0\t0\n", "outside 0..255");
  expectBadLine("label\tname\tr\tg\tb\n5\tliver\t3\n", "expected 5 tab-separated columns");
  expectBadLine("label\tr\tg\tb\n", "no 'name' column");
  expectBadLine("label\tname\tr\n", "not all of the colour columns");
  expectBadLine("label\tname\nfive\tliver\n", "bad label id 'five'");
  expectBadLine("label\tname\n5\t\n", "empty name");
  expectBadLine("1 tissue 128 174\n", "expected 'id name r g b a'");
}

TEST(LabelTableIo, FormatThenParseKeepsTheTable) {
  LabelTable table;
  table.add({5, "liver", {{221, 130, 101}}});
  table.add({1, "left kidney", {{10, 20, 30}}});
  const std::string text = formatLabelTable(table);
  EXPECT_EQ(text, "label\tname\tr\tg\tb\n1\tleft kidney\t10\t20\t30\n5\tliver\t221\t130\t101\n");
  const LabelTable parsed = parseLabelTable(text, "round-trip.tsv");
  ASSERT_EQ(parsed.entries.size(), 2u);
  for (std::size_t n = 0; n < 2; ++n) {
    EXPECT_EQ(parsed.entries[n].id, table.entries[n].id);
    EXPECT_EQ(parsed.entries[n].name, table.entries[n].name);
    EXPECT_EQ(parsed.entries[n].color, table.entries[n].color);
  }
}

TEST(LabelTableIo, RefusesNamesTheTsvCannotCarry) {
  LabelTable table;
  table.add({2, "two\tcolumns", {{0, 0, 0}}});
  EXPECT_THROW(formatLabelTable(table), BadInput);
}

TEST(LabelTableIo, WritesAtomicallyAndKeepsExistingFiles) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / "label_table_write";
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string path = (folder / "labels.tsv").string();
  LabelTable table;
  table.add({5, "liver", {{221, 130, 101}}});
  writeLabelTable(path, table);
  EXPECT_EQ(readTextFile(path), formatLabelTable(table));

  LabelTable other;
  other.add({6, "stomach", {{1, 2, 3}}});
  EXPECT_THROW(writeLabelTable(path, other), UsageError);
  EXPECT_EQ(readLabelTable(path).entries.front().name, "liver");
  writeLabelTable(path, other, WriteOptions{true});
  EXPECT_EQ(readLabelTable(path).entries.front().name, "stomach");
  EXPECT_EQ(std::distance(fs::directory_iterator(folder), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace vesalius::io
