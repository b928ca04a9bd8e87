// RT Structure Sets (io/dicom_rtstruct.h): the shipped CT's labels, a ring with a hole, an oblique head CT
// and a label map on the shipped dcmqi CT series written, read back with DCMTK's dcmrt and with our reader
// onto the same grid (voxel-boundary contours filled by the even-odd rule give the voxels back exactly);
// read onto a scan: an explicit table applied as to a DICOM SEG, a series of another frame of reference
// refused; found by content under any name; broken files refused in one line.
#include "vesalius/core/error.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"

#include "test_ct_3slice.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcstack.h>
#include <dcmtk/dcmrt/drtstrct.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

const std::string kRtStructSopClass = "1.2.840.10008.5.1.4.1.1.481.3";
const std::string kData = std::string(VESALIUS_TESTDATA);
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

// Voxels of each label that differ between two maps on one grid; prints them and the labels' sizes.
std::int64_t expectSameVoxels(const LabelMap& back, const LabelMap& map, const std::string& what) {
  EXPECT_EQ(back.labels.values.size(), map.labels.values.size());
  std::map<Label, std::int64_t> voxels, wrong;
  for (std::size_t n = 0; n < map.labels.values.size(); ++n) {
    ++voxels[map.labels.values[n]];
    if (back.labels.values[n] != map.labels.values[n]) ++wrong[map.labels.values[n]], ++wrong[back.labels.values[n]];
  }
  std::int64_t total = 0;
  for (const auto& [id, count] : wrong) total += count;
  std::cout << what << ": " << voxels.size() - voxels.count(0) << " labels, " << map.labels.values.size()
            << " voxels, " << total / 2 << " differ\n";
  for (const auto& [id, count] : wrong) ADD_FAILURE() << what << ": label " << id << " differs in " << count << " voxels";
  return total / 2;
}

struct ContourCounts {
  std::size_t contours = 0, longest = 0, longestBytes = 0;  // contours; the points and Contour Data bytes of the longest
};

// The DCMTK view: a valid RT Structure Set in Implicit VR with the given ROI names, colours and
// descriptions, and CLOSED_PLANAR contours.
void expectValidStructureSet(const std::string& path, const LabelMap& map, ContourCounts& counts) {
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  DcmDataset& data = *file.getDataset();
  EXPECT_EQ(element(data, DCM_SOPClassUID), kRtStructSopClass);
  EXPECT_EQ(element(data, DCM_Modality), "RTSTRUCT");
  EXPECT_EQ(data.getOriginalXfer(), EXS_LittleEndianImplicit);
  DRTStructureSetIOD rt;
  ASSERT_TRUE(rt.read(data).good());
  EXPECT_TRUE(rt.isValid());
  std::set<Label> present(map.labels.values.begin(), map.labels.values.end());
  present.erase(0);
  DRTStructureSetROISequence& rois = rt.getStructureSetROISequence();
  DRTROIContourSequence& roiContours = rt.getROIContourSequence();
  ASSERT_EQ(rois.getNumberOfItems(), present.size());
  ASSERT_EQ(roiContours.getNumberOfItems(), present.size());
  EXPECT_EQ(rt.getRTROIObservationsSequence().getNumberOfItems(), present.size());
  OFString frameOfReference;
  ASSERT_EQ(rt.getReferencedFrameOfReferenceSequence().getNumberOfItems(), 1u);
  rt.getReferencedFrameOfReferenceSequence().getItem(0).getFrameOfReferenceUID(frameOfReference);
  EXPECT_FALSE(frameOfReference.empty());
  counts = {};
  std::size_t n = 0;
  for (Label id : present) {
    const LabelEntry* entry = map.table.find(id);
    ASSERT_NE(entry, nullptr) << id;
    DRTStructureSetROISequence::Item& roi = rois.getItem(n);
    OFString name, description, number, reference, referenced, type;
    roi.getROIName(name);
    roi.getROIDescription(description);
    roi.getROINumber(number);
    roi.getReferencedFrameOfReferenceUID(reference);
    EXPECT_EQ(std::string(name.c_str()), entry->name.substr(0, 64));
    EXPECT_EQ(std::string(description.c_str()), "label " + std::to_string(id));
    EXPECT_EQ(std::string(number.c_str()), std::to_string(n + 1));
    EXPECT_EQ(reference, frameOfReference);
    DRTROIContourSequence::Item& contour = roiContours.getItem(n);
    contour.getReferencedROINumber(referenced);
    EXPECT_EQ(referenced, number);
    for (int c = 0; c < 3; ++c) {
      Sint32 value = -1;
      contour.getROIDisplayColor(value, c);
      EXPECT_EQ(value, entry->color[c]) << entry->name;
    }
    DRTContourSequence& sequence = contour.getContourSequence();
    EXPECT_GT(sequence.getNumberOfItems(), 0u) << entry->name;
    for (std::size_t c = 0; c < sequence.getNumberOfItems(); ++c) {
      sequence.getItem(c).getContourGeometricType(type);
      EXPECT_EQ(type, "CLOSED_PLANAR");
      OFVector<Float64> data;
      sequence.getItem(c).getContourData(data);
      counts.longest = std::max(counts.longest, data.size() / 3);
    }
    counts.contours += sequence.getNumberOfItems();
    ++n;
  }
  DcmStack found;
  ASSERT_TRUE(data.findAndGetElements(DCM_ContourData, found).good());
  for (unsigned long e = 0; e < found.card(); ++e)
    counts.longestBytes = std::max(counts.longestBytes, std::size_t(found.elem(e)->getLength()));
}

TEST(DicomRtStruct, ShippedCtLabelsRoundTripExactly) {
  const std::string ct = kData + "/ct-abdomen-pelvis/";
  const LabelMap map = readLabelMap(ct + "example_seg_total_v1_for_example_ct.nii.gz", ct + "labels_total_v1.tsv");
  const std::string path = fresh("ct-abdomen-pelvis.rtstruct.dcm");
  writeDicomRtStruct(path, map, nullptr);
  ContourCounts counts;
  expectValidStructureSet(path, map, counts);
  const LabelMap back = readDicomRtStruct(path, map.labels.geometry);
  std::cout << "ct-abdomen-pelvis: " << counts.contours << " contours (the longest " << counts.longest
            << " points), " << fs::file_size(path) << " bytes\n";
  EXPECT_EQ(expectSameVoxels(back, map, "ct-abdomen-pelvis"), 0);
  for (const LabelEntry& e : back.table.entries) {
    const LabelEntry* written = map.table.find(e.id);
    ASSERT_NE(written, nullptr) << e.id;
    EXPECT_EQ(e.name, written->name);
    EXPECT_EQ(e.color, written->color) << e.name;
  }
  // Written through writeLabelMap too, with no tables beside it.
  EXPECT_TRUE(isDicomRtStructPath(path));
  EXPECT_FALSE(isDicomSegPath(path));
  EXPECT_TRUE(isDicomRtStructFile(path));
  EXPECT_FALSE(isDicomSegFile(path));
  EXPECT_EQ(labelMapFiles(path), std::vector<std::string>{path});
  const std::string viaLabelMap = fresh("via-label-map.RTSTRUCT.dcm");
  writeLabelMap(viaLabelMap, map);
  EXPECT_TRUE(isDicomRtStructFile(viaLabelMap));
  // Nothing is lost: an existing output is kept, and an input is never an output.
  EXPECT_THROW(writeDicomRtStruct(path, map, nullptr), UsageError);
  protectInput(viaLabelMap);
  EXPECT_THROW(writeDicomRtStruct(viaLabelMap, map, nullptr, {true}), UsageError);
}

// 9 x 8 x 3 voxels on a rotated, anisotropic grid. Label 4 is a ring (a square with a hole) on slices 0 and
// 1, with label 6 on one voxel inside the hole on slice 1; label 5 has two voxels touching at a corner.
TEST(DicomRtStruct, ARingWithAHoleRoundTrips) {
  LabelMap map;
  GridGeometry& g = map.labels.geometry;
  g.size = {9, 8, 3};
  g.spacing = {0.7, 0.9, 2.5};
  g.origin = {-10.5, 20.25, -100.125};
  g.direction = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  map.labels.values.assign(g.voxelCount(), 0);
  for (int k = 0; k < 2; ++k)
    for (int j = 1; j <= 5; ++j)
      for (int i = 1; i <= 5; ++i)
        if (i == 1 || i == 5 || j == 1 || j == 5) map.labels.at(i, j, k) = 4;
  map.labels.at(3, 3, 1) = 6;
  map.labels.at(7, 6, 2) = 5;
  map.labels.at(8, 7, 2) = 5;
  map.table.add({4, "ring", {{200, 10, 10}}});
  map.table.add({5, "corners", {{10, 200, 10}}});
  map.table.add({6, "island", {{10, 10, 200}}});
  const std::string path = fresh("ring.rtstruct.dcm");
  writeDicomRtStruct(path, map, nullptr);
  ContourCounts counts;
  expectValidStructureSet(path, map, counts);
  // The ring: an outer boundary and a hole on each of its two slices; the island one, the corners two.
  EXPECT_EQ(counts.contours, 4u + 1u + 2u);

  // Outer boundaries run counter-clockwise in the (i, j) plane, holes clockwise; a hole holds no corners.
  DRTStructureSetIOD rt;
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  ASSERT_TRUE(rt.read(*file.getDataset()).good());
  DRTContourSequence& ring = rt.getROIContourSequence().getItem(0).getContourSequence();
  std::vector<double> areas;
  for (std::size_t c = 0; c < ring.getNumberOfItems(); ++c) {
    OFVector<Float64> data;
    ring.getItem(c).getContourData(data);
    double area = 0;
    const std::size_t count = data.size() / 3;
    for (std::size_t n = 0; n < count; ++n) {
      const Eigen::Vector3d a = g.worldToIndex({data[3 * n], data[3 * n + 1], data[3 * n + 2]});
      const std::size_t m = (n + 1) % count;
      const Eigen::Vector3d b = g.worldToIndex({data[3 * m], data[3 * m + 1], data[3 * m + 2]});
      area += (a.x() * b.y() - b.x() * a.y()) / 2;
    }
    areas.push_back(area);
    std::cout << "ring contour " << c << ": " << count << " corners, signed area " << area << " voxels\n";
  }
  std::sort(areas.begin(), areas.end());
  ASSERT_EQ(areas.size(), 4u);
  const double expected[4] = {-9, -9, 25, 25};
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(areas[c], expected[c], 1e-9);

  const LabelMap back = readDicomRtStruct(path, g);
  EXPECT_EQ(expectSameVoxels(back, map, "ring"), 0);
  EXPECT_EQ(back.labels.at(3, 3, 0), 0);  // the hole
  EXPECT_EQ(back.labels.at(3, 3, 1), 6);
}

// A pitched head CT (oblique direction cosines, 0.81 x 0.81 x 2.4 mm): its skull is a ring in most slices.
TEST(DicomRtStruct, AnObliqueGridRoundTrips) {
  const Image scan = readScan(kData + "/oblique-ct/CT_pitch.nii.gz");
  const Eigen::Matrix3d& d = scan.geometry.direction;
  const double tilt = std::acos(std::min(1.0, d.cwiseAbs().colwise().maxCoeff().minCoeff())) * 180 / EIGEN_PI;
  std::cout << "CT_pitch: axes up to " << tilt << " degrees off the patient axes\n";
  EXPECT_GT(tilt, 1.0);
  LabelMap map;
  map.labels = Grid<Label>(scan.geometry, 0);
  for (std::size_t n = 0; n < scan.values.size(); ++n)
    map.labels.values[n] = scan.values[n] > 150 ? 2 : scan.values[n] > 40 ? 1 : 0;
  map.table.add({1, "soft", {{200, 100, 90}}});
  map.table.add({2, "dense", {{240, 240, 220}}});
  const std::string path = fresh("oblique.rtstruct.dcm");
  writeDicomRtStruct(path, map, nullptr);
  ContourCounts counts;
  expectValidStructureSet(path, map, counts);
  std::cout << "CT_pitch: " << counts.contours << " contours, the longest " << counts.longest << " points ("
            << counts.longestBytes << " bytes of Contour Data)\n";
  // More than the 65534 bytes a DS element holds in Explicit VR: the reason the file is Implicit VR.
  EXPECT_GT(counts.longestBytes, 65534u);
  const LabelMap back = readDicomRtStruct(path, scan.geometry);
  EXPECT_EQ(expectSameVoxels(back, map, "CT_pitch"), 0);
}

TEST(DicomRtStruct, RefersToTheSourceSeries) {
  const std::optional<DicomSourceSeries> source = readDicomSource(kCtFolder);
  ASSERT_TRUE(source);
  ASSERT_EQ(source->images.size(), 3u);
  const Image scan = readScan(kCtFolder);
  const LabelMap map = test::softTissueAndBone(scan);
  const std::string path = fresh("ct-3slice.rtstruct.dcm");
  writeDicomRtStruct(path, map, &*source);
  ContourCounts counts;
  expectValidStructureSet(path, map, counts);

  DcmFileFormat file, sourceFile;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  ASSERT_TRUE(sourceFile.loadFile((kCtFolder + "/01.dcm").c_str()).good());
  DcmDataset &data = *file.getDataset(), &ct = *sourceFile.getDataset();
  for (const DcmTagKey& tag : {DCM_StudyInstanceUID, DCM_PatientID, DCM_PatientName}) {
    EXPECT_EQ(element(data, tag), element(ct, tag)) << DcmTag(tag).getTagName();
    EXPECT_FALSE(element(data, tag).empty()) << DcmTag(tag).getTagName();
  }
  EXPECT_NE(element(data, DCM_SeriesInstanceUID), element(ct, DCM_SeriesInstanceUID));
  DRTStructureSetIOD rt;
  ASSERT_TRUE(rt.read(data).good());
  DRTReferencedFrameOfReferenceSequence::Item& frame = rt.getReferencedFrameOfReferenceSequence().getItem(0);
  OFString uid;
  frame.getFrameOfReferenceUID(uid);
  EXPECT_EQ(std::string(uid.c_str()), element(ct, DCM_FrameOfReferenceUID));
  ASSERT_EQ(frame.getRTReferencedStudySequence().getNumberOfItems(), 1u);
  DRTRTReferencedStudySequence::Item& study = frame.getRTReferencedStudySequence().getItem(0);
  study.getReferencedSOPInstanceUID(uid);
  EXPECT_EQ(std::string(uid.c_str()), element(ct, DCM_StudyInstanceUID));
  ASSERT_EQ(study.getRTReferencedSeriesSequence().getNumberOfItems(), 1u);
  DRTRTReferencedSeriesSequence::Item& series = study.getRTReferencedSeriesSequence().getItem(0);
  series.getSeriesInstanceUID(uid);
  EXPECT_EQ(std::string(uid.c_str()), element(ct, DCM_SeriesInstanceUID));
  std::set<std::string> listed;
  for (std::size_t n = 0; n < series.getContourImageSequence().getNumberOfItems(); ++n) {
    series.getContourImageSequence().getItem(n).getReferencedSOPInstanceUID(uid);
    listed.insert(uid.c_str());
  }
  EXPECT_EQ(listed.size(), 3u);

  // Every contour names the source image on its own slice.
  std::size_t checked = 0;
  DRTROIContourSequence& rois = rt.getROIContourSequence();
  for (std::size_t r = 0; r < rois.getNumberOfItems(); ++r) {
    DRTContourSequence& sequence = rois.getItem(r).getContourSequence();
    for (std::size_t c = 0; c < sequence.getNumberOfItems(); ++c, ++checked) {
      DRTContourSequence::Item& contour = sequence.getItem(c);
      ASSERT_EQ(contour.getContourImageSequence().getNumberOfItems(), 1u);
      contour.getContourImageSequence().getItem(0).getReferencedSOPInstanceUID(uid);
      const auto image = std::find_if(source->images.begin(), source->images.end(),
                                      [&](const DicomSourceImage& i) { return i.sopInstanceUid == uid.c_str(); });
      ASSERT_NE(image, source->images.end()) << uid;
      EXPECT_TRUE(listed.count(uid.c_str()));
      Float64 z = 0;
      contour.getContourData(z, 2);
      EXPECT_NEAR(image->position->z(), z, 1e-3) << uid;
    }
  }
  std::cout << "ct-3slice: " << checked << " contours refer to their slice's image\n";
  EXPECT_EQ(checked, counts.contours);
  EXPECT_EQ(expectSameVoxels(readDicomRtStruct(path, scan.geometry), map, "ct-3slice"), 0);
}

// The 3-slice series' two classes written as a structure set referring to the series.
struct OnTheSeries {
  DicomSourceSeries source;
  Image scan;
  LabelMap map;
  std::string path;
};

OnTheSeries writtenOnTheSeries(const std::string& name) {
  OnTheSeries written;
  const std::optional<DicomSourceSeries> source = readDicomSource(kCtFolder);
  EXPECT_TRUE(source);
  if (source) written.source = *source;
  written.scan = readScan(kCtFolder);
  written.map = test::softTissueAndBone(written.scan);
  written.path = fresh(name);
  writeDicomRtStruct(written.path, written.map, &written.source);
  return written;
}

// An explicit table takes the place of the ROIs' names and colours whole, and labels it leaves out are
// named "label_<id>": the rule readLabelMap applies to a DICOM SEG, checked against one written from the
// same map. Without a table the ROIs name themselves.
TEST(DicomRtStruct, AnExplicitTableReplacesTheRoiNamesAsForASeg) {
  const OnTheSeries written = writtenOnTheSeries("table-rule.rtstruct.dcm");
  const LabelMap& map = written.map;
  const std::string &rt = written.path, seg = fresh("table-rule.seg.dcm");
  writeDicomSeg(seg, map, &written.source);
  // The table names bone only, and gives soft tissue's name to a label the map does not have.
  const std::string table = fresh("table-rule.tsv");
  std::ofstream(table) << "label\tname\tr\tg\tb\n2\tcortical_bone\t10\t20\t30\n7\tsoft_tissue\t1\t2\t3\n";

  const LabelMap own = readDicomRtStructOntoScan(rt, kCtFolder);
  EXPECT_EQ(expectSameVoxels(own, map, "ct-3slice onto its series"), 0);
  ASSERT_EQ(own.table.entries.size(), 2u);
  EXPECT_EQ(own.table.find(1)->name, "soft_tissue");
  EXPECT_EQ(own.table.find(2)->name, "bone");

  const LabelMap named = readDicomRtStructOntoScan(rt, kCtFolder, table);
  const LabelMap segNamed = readLabelMap(seg, table);
  EXPECT_EQ(expectSameVoxels(named, map, "ct-3slice with a table"), 0);
  for (const LabelEntry& e : named.table.entries)
    std::cout << "RT Structure Set with the table: " << e.id << " " << e.name << " (" << int(e.color[0]) << ", "
              << int(e.color[1]) << ", " << int(e.color[2]) << ")\n";
  ASSERT_EQ(named.table.entries.size(), 3u);
  EXPECT_EQ(named.table.find(2)->name, "cortical_bone");
  EXPECT_EQ(named.table.find(2)->color, (std::array<std::uint8_t, 3>{{10, 20, 30}}));
  EXPECT_EQ(named.table.find(7)->name, "soft_tissue");
  EXPECT_EQ(named.table.find(1)->name, "label_1");
  EXPECT_EQ(named.table.find(1)->color, defaultLabelColor(1));
  ASSERT_EQ(segNamed.table.entries.size(), named.table.entries.size());
  for (const LabelEntry& e : segNamed.table.entries) {
    const LabelEntry* same = named.table.find(e.id);
    ASSERT_NE(same, nullptr) << e.id;
    EXPECT_EQ(same->name, e.name) << e.id;
    EXPECT_EQ(same->color, e.color) << e.id;
  }
}

// The contours are in one patient space with a scan of their own frame of reference (or of none: a NIfTI),
// and refused onto a series of another: TotalSegmentator's JPEG 2000 series for one written on dcmqi's.
TEST(DicomRtStruct, AScanOfAnotherFrameOfReferenceIsRefused) {
  const OnTheSeries written = writtenOnTheSeries("frame.rtstruct.dcm");
  const LabelMap& map = written.map;
  const DicomSourceSeries* source = &written.source;
  const std::string &rt = written.path, nifti = fresh("frame-ct.nii.gz");
  writeScan(nifti, written.scan);
  EXPECT_EQ(expectSameVoxels(readDicomRtStructOntoScan(rt, kCtFolder), map, "onto its own series"), 0);
  EXPECT_EQ(expectSameVoxels(readDicomRtStructOntoScan(rt, nifti), map, "onto a NIfTI of it"), 0);

  const std::string other = kData + "/dicom/ct-series-jpeg2000";
  const std::optional<DicomSourceSeries> otherSource = readDicomSource(other);
  ASSERT_TRUE(otherSource);
  std::cout << "frames of reference: " << source->frameOfReferenceUid << " and " << otherSource->frameOfReferenceUid
            << '\n';
  ASSERT_NE(otherSource->frameOfReferenceUid, source->frameOfReferenceUid);
  try {
    readDicomRtStructOntoScan(rt, other);
    ADD_FAILURE() << rt << " was read onto " << other;
  } catch (const BadInput& e) {
    const std::string message = e.what();
    std::cout << message << '\n';
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : {rt, other, source->frameOfReferenceUid, otherSource->frameOfReferenceUid,
                                    std::string("Frame of Reference")})
      EXPECT_NE(message.find(part), std::string::npos) << part << " not in: " << message;
  }
}

// A structure set is found by its content under any name (PACS exports often have no extension or .IMA);
// a NIfTI, a DICOM CT image, a SEG, a folder and a short file are not taken for one.
TEST(DicomRtStruct, FoundByItsContentUnderAnyName) {
  const Image scan = readScan(kCtFolder);
  const LabelMap map = test::softTissueAndBone(scan);
  const std::string rt = fresh("content.rtstruct.dcm"), bare = fresh("RS1"), ima = fresh("RS1.IMA"),
                    seg = fresh("content.dcm"), nifti = fresh("content.nii.gz"), tiny = fresh("tiny");
  writeDicomRtStruct(rt, map, nullptr);
  fs::copy_file(rt, bare);
  fs::copy_file(rt, ima);
  writeDicomSeg(seg, map, nullptr);
  writeLabelMap(nifti, map, {true});
  std::ofstream(tiny) << "DICM";
  for (const std::string& path : {rt, bare, ima}) EXPECT_TRUE(isDicomRtStructFile(path)) << path;
  for (const std::string& path : {seg, nifti, tiny, kCtFolder, kCtFolder + "/01.dcm", kData + "/nowhere"})
    EXPECT_FALSE(isDicomRtStructFile(path)) << path;
  EXPECT_EQ(expectSameVoxels(readDicomRtStruct(bare, scan.geometry), map, "RS1"), 0);
}

void expectOneLineBadInput(const std::string& path, const GridGeometry& grid, const std::string& fragment) {
  try {
    readDicomRtStruct(path, grid);
    ADD_FAILURE() << path << " was read";
  } catch (const BadInput& e) {
    const std::string message = e.what();
    std::cout << message << '\n';
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
  }
}

// A copy of `whole` with the first contour's points replaced by `points` (x, y, z each).
std::string withFirstContour(const std::string& whole, const std::string& name, const std::vector<double>& points) {
  DcmFileFormat file;
  EXPECT_TRUE(file.loadFile(whole.c_str()).good());
  DcmItem *roi = nullptr, *contour = nullptr;
  EXPECT_TRUE(file.getDataset()->findAndGetSequenceItem(DCM_ROIContourSequence, roi, 0).good());
  EXPECT_TRUE(roi->findAndGetSequenceItem(DCM_ContourSequence, contour, 0).good());
  std::string data;
  for (double v : points) data += (data.empty() ? "" : "\\") + std::to_string(v);
  contour->putAndInsertString(DCM_ContourData, data.c_str());
  contour->putAndInsertString(DCM_NumberOfContourPoints, std::to_string(points.size() / 3).c_str());
  const std::string path = fresh(name);
  EXPECT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
  return path;
}

TEST(DicomRtStruct, BrokenFilesAreRefusedInOneLine) {
  // An axis-aligned 6 x 5 x 4 grid, 1 x 1 x 2 mm, slices at z = 0, 2, 4, 6.
  LabelMap map;
  map.labels = Grid<Label>(GridGeometry{{6, 5, 4}, {0, 0, 0}, {1, 1, 2}, Eigen::Matrix3d::Identity()}, 0);
  const GridGeometry& g = map.labels.geometry;
  for (int k = 1; k < 3; ++k) map.labels.at(2, 2, k) = 1, map.labels.at(3, 2, k) = 1;
  map.table.add({1, "box", {{1, 2, 3}}});
  const std::string whole = fresh("whole.rtstruct.dcm");
  writeDicomRtStruct(whole, map, nullptr);
  EXPECT_EQ(expectSameVoxels(readDicomRtStruct(whole, g), map, "box"), 0);

  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = fresh("truncated.rtstruct.dcm");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 100);
  expectOneLineBadInput(cut, g, "");
  const std::string garbage = fresh("garbage.rtstruct.dcm");
  std::ofstream(garbage, std::ios::binary) << "this is not DICOM at all\n";
  expectOneLineBadInput(garbage, g, "");
  expectOneLineBadInput(kData + "/dicom/pydicom/CT_small.dcm", g, "not a DICOM RT Structure Set");

  expectOneLineBadInput(withFirstContour(whole, "two-points.rtstruct.dcm", {1, 1, 2, 3, 1, 2}), g,
                        "has 2 points; a closed contour needs at least 3");
  expectOneLineBadInput(withFirstContour(whole, "bent.rtstruct.dcm", {1, 1, 2, 3, 1, 2, 3, 3, 2, 1, 3, 3}), g,
                        "is not planar");
  expectOneLineBadInput(withFirstContour(whole, "between.rtstruct.dcm", {1, 1, 3, 3, 1, 3, 3, 3, 3}), g,
                        "lies on no slice of the grid");
  expectOneLineBadInput(withFirstContour(whole, "tilted.rtstruct.dcm", {1, 1, 2, 3, 1, 2, 3, 3, 4}), g,
                        "lies on no slice of the grid");
  expectOneLineBadInput(withFirstContour(whole, "beyond.rtstruct.dcm", {1, 1, 20, 3, 1, 20, 3, 3, 20}), g,
                        "lies off every slice of the grid");
  // A grid that ends before the contours' slices.
  GridGeometry shorter = g;
  shorter.size.z() = 1;
  expectOneLineBadInput(whole, shorter, "lies off every slice of the grid");

  // Read as a label map (a DICOM SEG), an RT Structure Set says what it is.
  try {
    readLabelMap(whole);
    ADD_FAILURE() << "an RT Structure Set was read as a label map";
  } catch (const BadInput& e) {
    std::cout << e.what() << '\n';
    EXPECT_NE(std::string(e.what()).find("an RT Structure Set"), std::string::npos) << e.what();
  }
  const std::string empty = fresh("empty.rtstruct.dcm");
  EXPECT_THROW(writeDicomRtStruct(empty, LabelMap{Grid<Label>(g, 0), {}}, nullptr), BadInput);
  EXPECT_FALSE(fs::exists(empty));
}

}  // namespace
}  // namespace vesalius::io
