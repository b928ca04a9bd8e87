// DICOM SEG objects (io/dicom_seg.h): a synthetic oblique label map and one on the shipped dcmqi CT series
// written, then read back with DCMTK itself and with our reader; broken files refused in one line.
#include "vesalius/core/error.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"

#include "test_ct_3slice.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

const std::string kSegSopClass = "1.2.840.10008.5.1.4.1.1.66.4";
const std::string& kCtFolder = test::kCt3SliceFolder;

std::string fresh(const std::string& name) {
  const fs::path dir = fs::path(VESALIUS_TEST_OUTPUT);
  fs::create_directories(dir);
  fs::remove(dir / name);
  return (dir / name).string();
}

std::string element(DcmItem& item, const DcmTagKey& tag) {
  OFString value;
  item.findAndGetOFStringArray(tag, value);
  return value.c_str();
}

// 7 x 5 x 6 voxels, rotated about an oblique axis, anisotropic. Label 3 is in every slice, 7 misses the
// first and last, 200 the first two and has a name with a space; 9 is listed but has no voxels.
LabelMap syntheticMap() {
  LabelMap map;
  GridGeometry& g = map.labels.geometry;
  g.size = {7, 5, 6};
  g.spacing = {0.7, 0.9, 2.5};
  g.origin = {-10.5, 20.25, -100.125};
  g.direction = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  map.labels.values.assign(g.voxelCount(), 0);
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 7; ++i) {
        Label& v = map.labels.at(i, j, k);
        if (i < 3 && j < 2) v = 3;
        else if (k >= 1 && k <= 4 && (i + j + k) % 3 == 0) v = 7;
        else if (k >= 2 && i == 6) v = 200;
      }
  map.table.add({3, "liver", {{221, 130, 101}}});
  map.table.add({7, "bone marrow", {{250, 250, 225}}});
  map.table.add({200, "a b", {{10, 200, 30}}});
  map.table.add({9, "absent", {{1, 2, 3}}});  // no voxels: no segment
  return map;
}

double maxDifference(const GridGeometry& a, const GridGeometry& b) {
  double d = (a.origin - b.origin).cwiseAbs().maxCoeff();
  d = std::max(d, (a.spacing - b.spacing).cwiseAbs().maxCoeff());
  d = std::max(d, (a.direction - b.direction).cwiseAbs().maxCoeff());
  // The far corner, which shows a direction error times the extent.
  const Eigen::Vector3d corner = a.size.cast<double>() - Eigen::Vector3d::Ones();
  return std::max(d, (a.indexToWorld(corner) - b.indexToWorld(corner)).norm());
}

// Checks every frame's bits, read straight from Pixel Data (frames packed bit after bit, least significant
// first), against the label of its segment on the slice at its Image Position (Patient). Returns the frames.
int expectFramesMatch(DcmDataset& data, const LabelMap& map, const std::vector<Label>& idOfSegment) {
  const GridGeometry& g = map.labels.geometry;
  const Uint8* bits = nullptr;
  unsigned long bytes = 0;
  EXPECT_TRUE(data.findAndGetUint8Array(DCM_PixelData, bits, &bytes).good());
  const std::size_t sliceSize = std::size_t(g.size.x()) * g.size.y();
  DcmItem* frame = nullptr;
  int frames = 0;
  for (long f = 0; data.findAndGetSequenceItem(DCM_PerFrameFunctionalGroupsSequence, frame, f).good(); ++f, ++frames) {
    DcmItem *position = nullptr, *segment = nullptr;
    EXPECT_TRUE(frame->findAndGetSequenceItem(DCM_PlanePositionSequence, position, 0).good());
    EXPECT_TRUE(frame->findAndGetSequenceItem(DCM_SegmentIdentificationSequence, segment, 0).good());
    Eigen::Vector3d p;
    for (int c = 0; c < 3; ++c) position->findAndGetFloat64(DCM_ImagePositionPatient, p[c], c);
    Uint16 number = 0;
    segment->findAndGetUint16(DCM_ReferencedSegmentNumber, number);
    const Eigen::Vector3d index = g.worldToIndex(p);
    EXPECT_LT((index - Eigen::Vector3d(0, 0, std::round(index.z()))).norm(), 1e-4) << "frame " << f;
    const int k = int(std::lround(index.z()));
    const Label id = idOfSegment.at(number - 1);
    std::size_t wrong = 0;
    for (std::size_t n = 0; n < sliceSize; ++n) {
      const std::size_t bit = f * sliceSize + n;
      wrong += bool((bits[bit / 8] >> (bit % 8)) & 1) != (map.labels.values[k * sliceSize + n] == id);
    }
    EXPECT_EQ(wrong, 0u) << "frame " << f << " (segment " << number << ", slice " << k << ")";
  }
  EXPECT_GE(bytes * 8, frames * sliceSize);
  return frames;
}

TEST(DicomSeg, SyntheticMapRoundTripsThroughDcmtkAndOurReader) {
  const LabelMap map = syntheticMap();
  const std::string path = fresh("synthetic.dcm");
  writeDicomSeg(path, map, nullptr);

  // DCMTK on its own: the SOP class, the segments and their frames.
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  DcmDataset& data = *file.getDataset();
  EXPECT_EQ(element(data, DCM_SOPClassUID), kSegSopClass);
  EXPECT_EQ(element(data, DCM_Modality), "SEG");
  EXPECT_EQ(element(data, DCM_SegmentationType), "BINARY");
  EXPECT_FALSE(element(data, DCM_StudyInstanceUID).empty());
  EXPECT_FALSE(element(data, DCM_FrameOfReferenceUID).empty());
  Sint32 frames = 0;
  data.findAndGetSint32(DCM_NumberOfFrames, frames);
  // 3: slices 0..5 (6); 7: slices 1..4 (4); 200: slices 2..5 (4); no edge frames needed.
  EXPECT_EQ(frames, 14);
  EXPECT_EQ(expectFramesMatch(data, map, {3, 7, 200}), 14);
  DcmSegmentation* raw = nullptr;
  ASSERT_TRUE(DcmSegmentation::loadFile(path.c_str(), raw).good());
  std::unique_ptr<DcmSegmentation> seg(raw);
  ASSERT_EQ(seg->getNumberOfSegments(), 3u);
  const std::vector<std::string> names{"liver", "bone marrow", "a b"};
  for (std::size_t n = 1; n <= 3; ++n) {
    OFString label;
    seg->getSegment(n)->getSegmentLabel(label);
    EXPECT_EQ(std::string(label.c_str()), names[n - 1]);
  }

  const DicomSegmentation back = readDicomSeg(path);
  EXPECT_FALSE(back.source);
  EXPECT_EQ(back.labelMap.labels.geometry.size, map.labels.geometry.size);
  const double geometryError = maxDifference(back.labelMap.labels.geometry, map.labels.geometry);
  std::cout << "synthetic: " << frames << " frames, geometry differs by at most " << geometryError << " mm\n";
  EXPECT_LT(geometryError, 1e-3);
  EXPECT_EQ(back.labelMap.labels.values, map.labels.values);
  ASSERT_EQ(back.labelMap.table.entries.size(), 3u);
  for (const LabelEntry& e : back.labelMap.table.entries) {
    const LabelEntry* written = map.table.find(e.id);
    ASSERT_NE(written, nullptr) << e.id;
    EXPECT_EQ(e.name, written->name);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(e.color[c], written->color[c], 1) << e.name;
    std::cout << "  " << e.id << " " << e.name << ": " << int(e.color[0]) << " " << int(e.color[1]) << " "
              << int(e.color[2]) << " (written " << int(written->color[0]) << " " << int(written->color[1]) << " "
              << int(written->color[2]) << ")\n";
  }
  // readLabelMap takes the same file as a label map.
  EXPECT_EQ(readLabelMap(path).labels.values, map.labels.values);
  EXPECT_EQ(labelMapFiles(path), std::vector<std::string>{path});
}

TEST(DicomSeg, EmptyEdgeSlicesKeepTheGrid) {
  LabelMap map = syntheticMap();
  for (int k : {0, 5})
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 7; ++i) map.labels.at(i, j, k) = 0;
  const std::string path = fresh("edges.dcm");
  writeDicomSeg(path, map, nullptr);
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  // 3: slices 1..4; 7: 1..4; 200: 2..4; and an empty frame of segment 1 on slices 0 and 5.
  EXPECT_EQ(expectFramesMatch(*file.getDataset(), map, {3, 7, 200}), 13);
  const LabelMap back = readDicomSeg(path).labelMap;
  EXPECT_EQ(back.labels.geometry.size, map.labels.geometry.size);
  EXPECT_LT(maxDifference(back.labels.geometry, map.labels.geometry), 1e-3);
  EXPECT_EQ(back.labels.values, map.labels.values);
}

TEST(DicomSeg, RefersToTheSourceSeries) {
  const std::optional<DicomSourceSeries> source = readDicomSource(kCtFolder);
  ASSERT_TRUE(source);
  ASSERT_EQ(source->images.size(), 3u);
  const Image scan = readScan(kCtFolder);
  const LabelMap map = test::softTissueAndBone(scan);
  const std::string path = fresh("ct-3slice.dcm");
  writeDicomSeg(path, map, &*source);

  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  DcmDataset& data = *file.getDataset();
  EXPECT_EQ(element(data, DCM_SOPClassUID), kSegSopClass);
  DcmFileFormat sourceFile;
  ASSERT_TRUE(sourceFile.loadFile((kCtFolder + "/01.dcm").c_str()).good());
  DcmDataset& ct = *sourceFile.getDataset();
  for (const DcmTagKey& tag : {DCM_StudyInstanceUID, DCM_FrameOfReferenceUID, DCM_PatientID, DCM_PatientName}) {
    EXPECT_EQ(element(data, tag), element(ct, tag)) << DcmTag(tag).getTagName();
    EXPECT_FALSE(element(data, tag).empty()) << DcmTag(tag).getTagName();
  }
  EXPECT_NE(element(data, DCM_SeriesInstanceUID), element(ct, DCM_SeriesInstanceUID));
  DcmItem* series = nullptr;
  ASSERT_TRUE(data.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).good());
  EXPECT_EQ(element(*series, DCM_SeriesInstanceUID), element(ct, DCM_SeriesInstanceUID));
  std::set<std::string> referenced, sources;
  DcmItem* instance = nullptr;
  for (long n = 0; series->findAndGetSequenceItem(DCM_ReferencedInstanceSequence, instance, n).good(); ++n)
    referenced.insert(element(*instance, DCM_ReferencedSOPInstanceUID));
  for (const char* name : {"01", "02", "03"}) {
    DcmFileFormat slice;
    ASSERT_TRUE(slice.loadFile((kCtFolder + "/" + name + ".dcm").c_str()).good());
    sources.insert(element(*slice.getDataset(), DCM_SOPInstanceUID));
  }
  EXPECT_EQ(referenced, sources);

  // Every frame derives from the source slice at its own position.
  DcmItem* perFrame = nullptr;
  Sint32 frames = 0;
  data.findAndGetSint32(DCM_NumberOfFrames, frames);
  std::cout << "ct-3slice: " << frames << " frames\n";
  for (long f = 0; f < frames; ++f) {
    ASSERT_TRUE(data.findAndGetSequenceItem(DCM_PerFrameFunctionalGroupsSequence, perFrame, f).good());
    DcmItem *position = nullptr, *derivation = nullptr, *sourceImage = nullptr;
    ASSERT_TRUE(perFrame->findAndGetSequenceItem(DCM_PlanePositionSequence, position, 0).good());
    ASSERT_TRUE(perFrame->findAndGetSequenceItem(DCM_DerivationImageSequence, derivation, 0).good()) << f;
    ASSERT_TRUE(derivation->findAndGetSequenceItem(DCM_SourceImageSequence, sourceImage, 0).good());
    Float64 z = 0;
    position->findAndGetFloat64(DCM_ImagePositionPatient, z, 2);
    const std::string uid = element(*sourceImage, DCM_ReferencedSOPInstanceUID);
    const auto match = std::find_if(source->images.begin(), source->images.end(),
                                    [&](const DicomSourceImage& i) { return i.sopInstanceUid == uid; });
    ASSERT_NE(match, source->images.end()) << uid;
    EXPECT_NEAR(match->position->z(), z, 1e-3) << uid;
  }

  const DicomSegmentation back = readDicomSeg(path);
  const double geometryError = maxDifference(back.labelMap.labels.geometry, map.labels.geometry);
  std::cout << "ct-3slice: geometry differs by at most " << geometryError << " mm\n";
  EXPECT_LT(geometryError, 1e-3);
  EXPECT_EQ(back.labelMap.labels.values, map.labels.values);
  ASSERT_TRUE(back.source);
  EXPECT_EQ(back.source->seriesInstanceUid, source->seriesInstanceUid);
  EXPECT_EQ(back.source->studyInstanceUid, source->studyInstanceUid);
  EXPECT_EQ(back.source->frameOfReferenceUid, source->frameOfReferenceUid);
  EXPECT_EQ(back.source->images.size(), 3u);
  // A SEG read as a source refers on to the same series.
  const std::optional<DicomSourceSeries> again = readDicomSource(path);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->seriesInstanceUid, source->seriesInstanceUid);
}

// TotalSegmentator's JPEG 2000 series is anonymised: no study or series UID, SOP UIDs in the file meta
// header only. A SEG on it keeps its frame of reference and names no images (it could not list their series).
TEST(DicomSeg, AnAnonymisedSeriesGivesItsFrameOfReferenceOnly) {
  const std::string folder = std::string(VESALIUS_TESTDATA) + "/dicom/ct-series-jpeg2000";
  const std::optional<DicomSourceSeries> source = readDicomSource(folder);
  ASSERT_TRUE(source);
  ASSERT_EQ(source->images.size(), 20u);
  std::set<std::string> instances;
  for (const DicomSourceImage& image : source->images) {
    EXPECT_EQ(image.sopClassUid, "1.2.840.10008.5.1.4.1.1.2");  // CT Image Storage
    EXPECT_TRUE(image.position);
    instances.insert(image.sopInstanceUid);
  }
  EXPECT_EQ(instances.size(), 20u);
  EXPECT_EQ(instances.count(""), 0u);
  EXPECT_TRUE(source->seriesInstanceUid.empty());
  EXPECT_EQ(source->frameOfReferenceUid, "1.3.12.2.1107.5.1.4.60064.30000022120807274275100000041");

  const Image scan = readScan(folder);
  LabelMap map;
  map.labels = Grid<Label>(scan.geometry, 0);
  for (std::size_t n = 0; n < scan.values.size(); ++n) map.labels.values[n] = scan.values[n] > 200;
  const std::string path = fresh("jpeg2000.dcm");
  writeDicomSeg(path, map, &*source);
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  DcmDataset& data = *file.getDataset();
  EXPECT_EQ(element(data, DCM_FrameOfReferenceUID), source->frameOfReferenceUid);
  EXPECT_FALSE(element(data, DCM_StudyInstanceUID).empty());
  DcmItem* item = nullptr;
  EXPECT_TRUE(data.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, item, 0).bad());
  ASSERT_TRUE(data.findAndGetSequenceItem(DCM_PerFrameFunctionalGroupsSequence, item, 0).good());
  DcmItem* derivation = nullptr;
  EXPECT_TRUE(item->findAndGetSequenceItem(DCM_DerivationImageSequence, derivation, 0).bad());
  const DicomSegmentation back = readDicomSeg(path);
  EXPECT_EQ(back.labelMap.labels.values, map.labels.values);
  EXPECT_LT(maxDifference(back.labelMap.labels.geometry, map.labels.geometry), 1e-3);
}

void expectOneLineBadInput(const std::string& path, const std::string& fragment) {
  try {
    readDicomSeg(path);
    ADD_FAILURE() << path << " was read";
  } catch (const BadInput& e) {
    const std::string message = e.what();
    std::cout << message << '\n';
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

TEST(DicomSeg, BrokenFilesAreRefusedInOneLine) {
  const std::string whole = fresh("whole.dcm");
  writeDicomSeg(whole, syntheticMap(), nullptr);
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = fresh("truncated.dcm");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 200);
  expectOneLineBadInput(cut, "");
  EXPECT_THROW(readLabelMap(cut), BadInput);
  const std::string garbage = fresh("garbage.dcm");
  std::ofstream(garbage, std::ios::binary) << "this is not DICOM at all\n";
  expectOneLineBadInput(garbage, "");
  expectOneLineBadInput(std::string(VESALIUS_TESTDATA) + "/dicom/pydicom/CT_small.dcm", "not a DICOM segmentation");
  EXPECT_THROW(writeDicomSeg(fresh("empty.dcm"), LabelMap{Grid<Label>(syntheticMap().labels.geometry, 0), {}}, nullptr),
               BadInput);
  EXPECT_FALSE(fs::exists(fresh("empty.dcm")));
}

}  // namespace
}  // namespace vesalius::io
