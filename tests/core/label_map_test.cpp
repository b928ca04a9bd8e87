// LabelTable: sorted entries, lookup by id and by name (case-insensitive), resolving what users type.
#include "vesalius/core/error.h"
#include "vesalius/core/label_map.h"

#include <gtest/gtest.h>

namespace vesalius {
namespace {

LabelTable abdomen() {
  LabelTable t;
  t.add({5, "Liver", {{200, 100, 80}}});
  t.add({2, "bone", {{240, 240, 220}}});
  t.add({9, "Skin", {{177, 122, 101}}});
  return t;
}

TEST(LabelTable, AddKeepsEntriesSortedAndReplacesById) {
  LabelTable t = abdomen();
  ASSERT_EQ(t.entries.size(), 3u);
  EXPECT_EQ(t.entries[0].id, 2);
  EXPECT_EQ(t.entries[1].id, 5);
  EXPECT_EQ(t.entries[2].id, 9);
  t.add({5, "hepar", {{1, 2, 3}}});
  ASSERT_EQ(t.entries.size(), 3u);
  EXPECT_EQ(t.entries[1].name, "hepar");
  EXPECT_EQ(t.entries[1].color[2], 3);
}

TEST(LabelTable, FindsByIdAndByNameIgnoringCase) {
  const LabelTable t = abdomen();
  ASSERT_NE(t.find(Label(5)), nullptr);
  EXPECT_EQ(t.find(Label(5))->name, "Liver");
  EXPECT_EQ(t.find(Label(3)), nullptr);
  EXPECT_EQ(t.find(Label(0)), nullptr);
  ASSERT_NE(t.find(std::string("LIVER")), nullptr);
  EXPECT_EQ(t.find(std::string("LIVER"))->id, 5);
  EXPECT_EQ(t.find(std::string("Bone"))->id, 2);
  EXPECT_EQ(t.find(std::string("kidney")), nullptr);
}

TEST(LabelTable, ResolvesIdsAndNames) {
  const LabelTable t = abdomen();
  EXPECT_EQ(t.resolve("5"), 5);
  EXPECT_EQ(t.resolve("liver"), 5);
  EXPECT_EQ(t.resolve("SKIN"), 9);
  EXPECT_EQ(t.resolve("2"), 2);
  // A label map read without a table has ids but no names; those ids must still be usable.
  EXPECT_EQ(t.resolve("7"), 7);
  EXPECT_EQ(LabelTable().resolve("12"), 12);
  EXPECT_THROW(t.resolve("kidney"), UsageError);
  EXPECT_THROW(t.resolve("70000"), UsageError);
  EXPECT_THROW(t.resolve("-3"), UsageError);
  EXPECT_THROW(t.resolve("5abc"), UsageError);
  EXPECT_THROW(t.resolve(""), UsageError);
}

TEST(LabelTable, DefaultColorsAreStableAndDistinct) {
  EXPECT_EQ(defaultLabelColor(3), defaultLabelColor(3));
  for (Label id = 1; id < 20; ++id) EXPECT_NE(defaultLabelColor(id), defaultLabelColor(Label(id + 1)));
}

}  // namespace
}  // namespace vesalius
