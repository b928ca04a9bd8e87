// 3D Slicer segmentations (.seg.nrrd): files Slicer wrote (lassoan/slicerio's test data, testdata/slicer),
// their layers and overlaps, and ours written and read back.
#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/slicer_segmentation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;
using Rgb = std::array<std::uint8_t, 3>;

const std::string kSeg = std::string(VESALIUS_TESTDATA) + "/slicer/Segmentation.seg.nrrd";
const std::string kOverlapping = std::string(VESALIUS_TESTDATA) + "/slicer/SegmentationOverlapping.seg.nrrd";

// What the header of Segmentation.seg.nrrd says (Segment<i>_Name, _LabelValue, _Color * 255 rounded) and
// the voxels each value holds in its gzip data (counted with Python's gzip, independently of ITK).
struct Expected {
  std::string name;
  Label value;
  Rgb color;
  std::int64_t voxels;
};
const std::vector<Expected> kSegments{
    {"ribs", 1, {{253, 232, 158}}, 8487},
    {"cervical vertebral column", 2, {{255, 255, 207}}, 1216},
    {"thoracic vertebral column", 3, {{226, 202, 134}}, 2712},
    {"lumbar vertebral column", 4, {{212, 188, 102}}, 3259},
    {"right lung", 5, {{22, 197, 71}}, 34450},
    {"left lung", 6, {{197, 25, 99}}, 33700},
    {"tissue", 7, {{128, 174, 128}}, 154589},
};

std::int64_t count(const std::vector<Label>& values, Label id) {
  return std::count(values.begin(), values.end(), id);
}

void expectSegments(const LabelMap& map, const std::string& what) {
  EXPECT_EQ(map.table.entries.size(), kSegments.size()) << what;
  for (const Expected& e : kSegments) {
    ASSERT_NE(map.table.find(e.name), nullptr) << what << ": " << e.name;
    EXPECT_EQ(map.table.resolve(e.name), e.value) << what;
    EXPECT_EQ(map.table.find(e.value)->color, e.color) << what << ": " << e.name;
    EXPECT_EQ(count(map.labels.values, e.value), e.voxels) << what << ": " << e.name;
  }
}

TEST(SlicerSegmentation, ReadsAOneLayerSegmentation) {
  const SlicerSegmentation seg = readSlicerSegmentation(kSeg);
  ASSERT_EQ(seg.layers.size(), 1u);
  ASSERT_EQ(seg.segments.size(), 7u);
  EXPECT_EQ(seg.segments[0].id, "Segment_1");
  EXPECT_EQ(seg.segments[0].extent, (std::array<int, 6>{{0, 124, 0, 127, 0, 33}}));
  const GridGeometry& g = seg.layers[0].geometry;
  EXPECT_EQ(g.size, Eigen::Vector3i(128, 128, 34));
  // "space directions: (-3.04687595367432,0,0) (0,-3.04687595367432,0) (0,0,9.99...)", LPS
  EXPECT_NEAR(g.spacing.x(), 3.04687595367432, 1e-9);
  EXPECT_NEAR(g.spacing.z(), 10.0, 1e-9);
  EXPECT_NEAR(g.direction(0, 0), -1.0, 1e-12);
  EXPECT_NEAR(g.origin.x(), 193.09599304199222, 1e-9);
  EXPECT_NEAR(g.origin.z(), -340.24999999999994, 1e-9);

  const LabelMap map = readLabelMap(kSeg);
  expectSegments(map, "readLabelMap");
  std::int64_t labelled = 0;
  for (const Expected& e : kSegments) labelled += e.voxels;
  std::cout << "Segmentation.seg.nrrd: " << map.table.entries.size() << " segments, " << labelled
            << " labelled voxels of " << map.labels.values.size() << "\n";
  EXPECT_EQ(count(map.labels.values, 0), std::int64_t(map.labels.values.size()) - labelled);
}

TEST(SlicerSegmentation, ReadsLayersAndRefusesToMergeOverlaps) {
  const SlicerSegmentation seg = readSlicerSegmentation(kOverlapping);
  ASSERT_EQ(seg.layers.size(), 2u);
  ASSERT_EQ(seg.segments.size(), 8u);
  EXPECT_EQ(seg.segments[7].name, "overlapping sphere");
  EXPECT_EQ(seg.segments[7].layer, 1);
  EXPECT_EQ(seg.segments[7].labelValue, 1);
  const std::vector<LabelMap> layers = segmentationLayerMaps(seg);
  ASSERT_EQ(layers.size(), 2u);
  expectSegments(layers[0], "layer 0");
  EXPECT_EQ(layers[1].table.entries.size(), 1u);
  EXPECT_EQ(layers[1].table.resolve("overlapping sphere"), 1);
  EXPECT_EQ(count(layers[1].labels.values, 1), 19139);

  // Shared voxels of the sphere with each layer-0 segment, counted in the file's data independently.
  const std::vector<std::pair<std::string, std::int64_t>> kShared{
      {"ribs", 491}, {"right lung", 118}, {"left lung", 8723}, {"tissue", 6182}};
  const std::vector<SegmentOverlap> overlaps = segmentOverlaps(seg);
  ASSERT_EQ(overlaps.size(), kShared.size());
  for (std::size_t k = 0; k < overlaps.size(); ++k) {
    EXPECT_EQ(seg.segments[overlaps[k].first].name, kShared[k].first);
    EXPECT_EQ(seg.segments[overlaps[k].second].name, "overlapping sphere");
    EXPECT_EQ(overlaps[k].voxels, kShared[k].second) << kShared[k].first;
  }
  try {
    readLabelMap(kOverlapping);
    ADD_FAILURE() << "overlapping segments were merged into one label map";
  } catch (const BadInput& error) {
    const std::string message = error.what();
    std::cout << message << '\n';
    EXPECT_EQ(message.rfind(kOverlapping + ": segments overlap", 0), 0u) << message;
    EXPECT_NE(message.find("'ribs' (layer 0, value 1) and 'overlapping sphere' (layer 1, value 1) share 491 voxels"),
              std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
}

// Layers that do not overlap merge; a later layer's value taken by an earlier segment gets a free id.
TEST(SlicerSegmentation, MergesLayersThatDoNotOverlap) {
  GridGeometry geometry;
  geometry.size = {5, 4, 3};
  SlicerSegmentation seg;
  seg.layers.assign(3, Grid<Label>(geometry, 0));
  seg.segments = {{"a", "liver", {{1, 2, 3}}, 1, 0, {}},
                  {"b", "kidney", {{4, 5, 6}}, 2, 0, {}},
                  {"c", "tumour", {{7, 8, 9}}, 1, 1, {}},
                  {"d", "cyst", {{10, 11, 12}}, 7, 2, {}}};
  seg.layers[0].values[0] = 1;
  seg.layers[0].values[1] = 2;
  seg.layers[1].values[2] = 1;
  seg.layers[1].values[3] = 1;
  seg.layers[2].values[4] = 7;
  EXPECT_TRUE(segmentOverlaps(seg).empty());
  const LabelMap map = mergeSegmentationLayers(seg, "layers.seg.nrrd");
  ASSERT_EQ(map.table.entries.size(), 4u);
  EXPECT_EQ(map.table.resolve("liver"), 1);
  EXPECT_EQ(map.table.resolve("kidney"), 2);
  const Label tumour = map.table.resolve("tumour");
  EXPECT_TRUE(tumour != 1 && tumour != 2 && tumour != 7) << tumour;
  EXPECT_EQ(map.table.resolve("cyst"), 7);
  EXPECT_EQ(map.table.find(tumour)->color, (Rgb{{7, 8, 9}}));
  EXPECT_EQ(map.labels.values[2], tumour);
  EXPECT_EQ(map.labels.values[3], tumour);
  EXPECT_EQ(map.labels.values[4], 7);
  EXPECT_EQ(count(map.labels.values, 0), geometry.voxelCount() - 5);
}

// Ours -> .seg.nrrd -> ours: the labels, names, colours and geometry, for Slicer's file and for maps of
// other shapes (ids above 255, an entry with no voxels, a voxel value with no entry, oblique axes).
TEST(SlicerSegmentation, WrittenSegmentationsReadBackEqual) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / "seg-round-trip";
  fs::remove_all(folder);
  fs::create_directories(folder);

  std::vector<std::pair<std::string, LabelMap>> inputs{{"slicer", readLabelMap(kSeg)}};
  GridGeometry oblique;
  oblique.size = {7, 5, 3};
  oblique.spacing = {0.7, 0.9, 2.5};
  oblique.origin = {-12.5, 30.25, 101};
  const double c = std::cos(0.3), s = std::sin(0.3);
  oblique.direction << c, -s, 0, s, c, 0, 0, 0, 1;
  LabelMap wide{Grid<Label>(oblique, 0), {}};
  wide.table.add({3, "liver", {{221, 130, 101}}});
  wide.table.add({300, "vertebrae L5", {{0, 0, 0}}});
  wide.table.add({4000, "not present", {{255, 255, 255}}});
  wide.labels.values[8] = 3;
  wide.labels.values[50] = 300;
  wide.labels.values[104] = 17;  // no entry: written as "label_17"
  inputs.emplace_back("oblique", wide);

  for (const auto& [what, map] : inputs) {
    const std::string path = (folder / (what + ".seg.nrrd")).string();
    writeLabelMap(path, map);
    EXPECT_TRUE(labelTableSidecarPaths(path).empty());
    for (const char* extension : {".tsv", ".ctbl", ".label.txt"})
      EXPECT_FALSE(fs::exists(folder / (what + extension))) << what;
    const SlicerSegmentation seg = readSlicerSegmentation(path);
    ASSERT_EQ(seg.layers.size(), 1u);
    const LabelMap back = readLabelMap(path);
    EXPECT_EQ(back.labels.values, map.labels.values) << what;
    EXPECT_TRUE(back.labels.geometry.size == map.labels.geometry.size) << what;
    EXPECT_LT((back.labels.geometry.origin - map.labels.geometry.origin).norm(), 1e-9) << what;
    EXPECT_LT((back.labels.geometry.direction - map.labels.geometry.direction).norm(), 1e-9) << what;
    EXPECT_LT((back.labels.geometry.spacing - map.labels.geometry.spacing).norm(), 1e-9) << what;
    for (const LabelEntry& entry : map.table.entries) {
      const LabelEntry* found = back.table.find(entry.id);
      ASSERT_NE(found, nullptr) << what << ": " << entry.name;
      EXPECT_EQ(found->name, entry.name) << what;
      EXPECT_EQ(found->color, entry.color) << what << ": " << entry.name;
    }
    std::cout << what << ": " << seg.segments.size() << " segments written and read back\n";
  }
  // Extents are the voxel bounding boxes, and an empty segment has Slicer's empty extent.
  const SlicerSegmentation seg = readSlicerSegmentation((folder / "oblique.seg.nrrd").string());
  ASSERT_EQ(seg.segments.size(), 4u);  // 3, 17, 300, 4000
  EXPECT_EQ(seg.segments[0].labelValue, 3);
  EXPECT_EQ(seg.segments[0].extent, (std::array<int, 6>{{1, 1, 1, 1, 0, 0}}));  // voxel 8 = (1, 1, 0)
  EXPECT_EQ(seg.segments[1].name, "label_17");
  EXPECT_EQ(seg.segments[3].extent, (std::array<int, 6>{{0, -1, 0, -1, 0, -1}}));
  EXPECT_EQ(seg.segments[2].extent, (std::array<int, 6>{{1, 1, 2, 2, 1, 1}}));  // voxel 50 = (1, 2, 1)
  EXPECT_THROW(writeLabelMap((folder / "oblique.seg.nrrd").string(), wide), UsageError);  // no clobber

  // The NRRD header (plain text before the gzip data) holds every field Slicer's storage node reads.
  std::ifstream in(folder / "oblique.seg.nrrd", std::ios::binary);
  std::string header, line;
  while (std::getline(in, line) && !line.empty()) header += line + "\n";
  for (int i = 0; i < 4; ++i)
    for (const char* field : {"ID", "Name", "Color", "ColorAutoGenerated", "LabelValue", "Layer", "Extent",
                              "NameAutoGenerated", "Tags"})
      EXPECT_NE(header.find("\nSegment" + std::to_string(i) + "_" + field + ":="), std::string::npos)
          << "Segment" << i << "_" << field << " missing from\n" << header;
  for (const char* field : {"\nSegmentation_MasterRepresentation:=Binary labelmap\n",
                            "\nSegmentation_ContainedRepresentationNames:=Binary labelmap|\n",
                            "\nSegmentation_ReferenceImageExtentOffset:=0 0 0\n", "\nSegment2_Name:=vertebrae L5\n",
                            "\nSegment0_Tags:=|\n", "\nspace: left-posterior-superior\n", "\nkinds: domain domain domain\n"})
    EXPECT_NE(header.find(field), std::string::npos) << field << " missing from\n" << header;
}

}  // namespace
}  // namespace vesalius::io
