// DICOM SEG output through the `vesalius` program: `segment --out X.dcm` on the shipped DICOM series
// (dcmqi's 3-slice CT; TotalSegmentator's JPEG 2000 series, anonymised without study and series UIDs)
// read back with DCMTK and with our reader against `segment --out X.nii.gz`; `labels` passing the
// references on; `info` on a SEG; a cut file refused in one line; `segment` and `labels` writing RT
// Structure Sets (.rtstruct.dcm) that refer to the series and fill back to the NIfTI's voxels; `labels`
// and `surface` reading them onto the scan --grid names, and refusing them without --grid; one without an
// extension found by its content, one of another frame of reference refused; `reference torso` and `pose`
// reading one with --grid as they read the same map in NIfTI, `reference organs` and `patient` reading one
// with --grid before their work.
#include "run_command.h"
#include "test_ct_3slice.h"
#include "test_data.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
const std::string kSegSopClass = "1.2.840.10008.5.1.4.1.1.66.4";

std::string fresh(const std::string& name) {
  const fs::path path = fs::path(outputDir()) / name;
  fs::remove(path);
  for (const std::string& table : io::labelTableSidecarPaths(path.string())) fs::remove(table);
  const std::string stem = path.string().substr(0, path.string().size() - fileExtension(path.string()).size());
  fs::remove(stem + ".png");  // segment's picture
  return path.string();
}

std::string freshFolder(const std::string& name) {
  const fs::path path = fs::path(outputDir()) / name;
  fs::remove_all(path);
  return path.string();
}

std::string element(DcmItem& item, const DcmTagKey& tag) {
  OFString value;
  item.findAndGetOFStringArray(tag, value);
  return value.c_str();
}

// Series, study and frame of reference UIDs and SOP instance UIDs (dataset, else meta header) of a folder.
struct SourceUids {
  std::string series, study, frameOfReference;
  std::set<std::string> instances;
};

SourceUids sourceUids(const std::string& folder) {
  SourceUids uids;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    DcmFileFormat file;
    if (file.loadFile(entry.path().c_str()).bad()) continue;
    DcmDataset& data = *file.getDataset();
    uids.series = element(data, DCM_SeriesInstanceUID);
    uids.study = element(data, DCM_StudyInstanceUID);
    uids.frameOfReference = element(data, DCM_FrameOfReferenceUID);
    std::string instance = element(data, DCM_SOPInstanceUID);
    if (instance.empty()) instance = element(*file.getMetaInfo(), DCM_MediaStorageSOPInstanceUID);
    uids.instances.insert(instance);
  }
  return uids;
}

// Segments the series twice, as a SEG and as NIfTI, and checks the SEG against the NIfTI and the source.
void checkSegmentedSeries(const std::string& folder, const std::string& name) {
  const std::string seg = fresh(name + ".seg.dcm"), nifti = fresh(name + ".nii.gz");
  CommandResult r = runVesalius({"segment", "--scan", folder, "--modality", "ct", "--out", seg});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runVesalius({"segment", "--scan", folder, "--modality", "ct", "--out", nifti});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_FALSE(fs::exists(fs::path(seg).replace_extension(".tsv")));  // the SEG carries its names

  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(seg.c_str()).good());
  DcmDataset& data = *file.getDataset();
  EXPECT_EQ(element(data, DCM_SOPClassUID), kSegSopClass);
  const SourceUids source = sourceUids(folder);
  EXPECT_EQ(element(data, DCM_FrameOfReferenceUID), source.frameOfReference);
  DcmItem* series = nullptr;
  if (source.series.empty()) {
    // An anonymised series: its images cannot be listed under it.
    EXPECT_TRUE(data.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).bad());
  } else {
    EXPECT_EQ(element(data, DCM_StudyInstanceUID), source.study);
    ASSERT_TRUE(data.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).good());
    EXPECT_EQ(element(*series, DCM_SeriesInstanceUID), source.series);
    std::set<std::string> referenced;
    DcmItem* instance = nullptr;
    for (long n = 0; series->findAndGetSequenceItem(DCM_ReferencedInstanceSequence, instance, n).good(); ++n)
      referenced.insert(element(*instance, DCM_ReferencedSOPInstanceUID));
    EXPECT_EQ(referenced, source.instances);
  }

  DcmSegmentation* raw = nullptr;
  ASSERT_TRUE(DcmSegmentation::loadFile(seg.c_str(), raw).good());
  std::unique_ptr<DcmSegmentation> dcmtk(raw);
  const LabelMap expected = io::readLabelMap(nifti);
  std::set<std::string> dcmtkNames, expectedNames;
  for (std::size_t n = 1; n <= dcmtk->getNumberOfSegments(); ++n) {
    OFString label;
    dcmtk->getSegment(n)->getSegmentLabel(label);
    dcmtkNames.insert(label.c_str());
  }
  for (const LabelEntry& e : expected.table.entries)
    if (std::count(expected.labels.values.begin(), expected.labels.values.end(), e.id)) expectedNames.insert(e.name);
  EXPECT_EQ(dcmtkNames, expectedNames);

  const io::DicomSegmentation back = io::readDicomSeg(seg);
  const GridGeometry &a = back.labelMap.labels.geometry, &b = expected.labels.geometry;
  const Eigen::Vector3d corner = b.size.cast<double>() - Eigen::Vector3d::Ones();
  const double error = std::max({(a.origin - b.origin).norm(), (a.spacing - b.spacing).cwiseAbs().maxCoeff(),
                                 (a.indexToWorld(corner) - b.indexToWorld(corner)).norm()});
  std::size_t differing = 0;
  for (std::size_t n = 0; n < expected.labels.values.size(); ++n)
    differing += back.labelMap.labels.values[n] != expected.labels.values[n];
  std::cout << name << ": " << dcmtk->getNumberOfFrames() << " frames, " << fs::file_size(seg) << " bytes, "
            << dcmtkNames.size() << " segments, geometry differs by " << error << " mm, " << differing
            << " voxels differ from the NIfTI\n";
  EXPECT_EQ(a.size, b.size);
  EXPECT_LT(error, 1e-3);
  EXPECT_EQ(differing, 0u);
  for (const LabelEntry& e : back.labelMap.table.entries) {
    ASSERT_NE(expected.table.find(e.id), nullptr) << e.id;
    EXPECT_EQ(e.name, expected.table.find(e.id)->name);
  }
  if (!source.series.empty()) {
    ASSERT_TRUE(back.source);
    EXPECT_EQ(back.source->seriesInstanceUid, source.series);
  }
}

TEST(CliDicomSeg, SegmentWritesASegReferringToTheDcmqiSeries) {
  checkSegmentedSeries(kData + "/dicom/ct-3slice-dcmqi/ct-3slice", "ct-3slice");
}

TEST(CliDicomSeg, SegmentOfAnAnonymisedSeriesKeepsItsFrameOfReference) {
  checkSegmentedSeries(kData + "/dicom/ct-series-jpeg2000", "ct-jpeg2000");
}

TEST(CliDicomSeg, LabelsPassesTheReferencesOnAndInfoDescribesTheSeg) {
  const std::string folder = kData + "/dicom/ct-3slice-dcmqi/ct-3slice";
  const std::string seg = fresh("labels-in.seg.dcm"), bone = fresh("bone.dcm"), nifti = fresh("labels-in.nii.gz"),
                    fromNifti = fresh("bone-from-nifti.dcm");
  ASSERT_EQ(runVesalius({"segment", "--scan", folder, "--out", seg}).exitCode, 0);
  CommandResult r = runVesalius({"labels", "extract", "--labels", seg, "--label", "bone", "--out", bone});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const SourceUids source = sourceUids(folder);
  const io::DicomSegmentation extracted = io::readDicomSeg(bone);
  ASSERT_EQ(extracted.labelMap.table.entries.size(), 1u);
  EXPECT_EQ(extracted.labelMap.table.entries.front().name, "bone");
  ASSERT_TRUE(extracted.source);
  EXPECT_EQ(extracted.source->seriesInstanceUid, source.series);
  EXPECT_EQ(extracted.source->studyInstanceUid, source.study);

  // A NIfTI input refers to the series named with --dicom-series.
  ASSERT_EQ(runVesalius({"segment", "--scan", folder, "--out", nifti}).exitCode, 0);
  r = runVesalius({"labels", "extract", "--labels", nifti, "--label", "bone", "--out", fromNifti, "--dicom-series",
                   folder});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::DicomSegmentation fromNiftiSeg = io::readDicomSeg(fromNifti);
  ASSERT_TRUE(fromNiftiSeg.source);
  EXPECT_EQ(fromNiftiSeg.source->seriesInstanceUid, source.series);
  EXPECT_EQ(fromNiftiSeg.labelMap.labels.values, extracted.labelMap.labels.values);
  r = runVesalius({"labels", "extract", "--labels", nifti, "--label", "bone", "--out", fresh("bone.nii.gz"),
                   "--dicom-series", folder});
  EXPECT_EQ(r.exitCode, 2) << r.err;

  r = runVesalius({"info", bone});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out;
  expectContains(r.out, "DICOM segmentation, 1 segments");
  expectContains(r.out, "refers to    series " + source.series + " (3 images)");
  expectContains(r.out, "bone");
}

TEST(CliDicomSeg, ACutSegIsOneLineAndExitThree) {
  const std::string whole = fresh("whole.dcm");
  ASSERT_EQ(runVesalius({"segment", "--scan", kData + "/dicom/ct-3slice-dcmqi/ct-3slice", "--out", whole}).exitCode, 0);
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = fresh("cut.dcm");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"info", cut},
        std::vector<std::string>{"labels", "extract", "--labels", cut, "--label", "bone", "--out", fresh("x.dcm")}}) {
    const CommandResult r = runVesalius(args);
    std::cout << r.err;
    EXPECT_EQ(r.exitCode, 3) << args[0];
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    expectContains(r.err, cut);
  }
  EXPECT_FALSE(fs::exists(fresh("x.dcm")));
}

TEST(CliDicomSeg, SegmentAndLabelsWriteRtStructsReferringToTheSeries) {
  const std::string folder = kData + "/dicom/ct-3slice-dcmqi/ct-3slice";
  const std::string rt = fresh("ct-3slice.rtstruct.dcm"), nifti = fresh("ct-3slice-rt.nii.gz"),
                    bone = fresh("bone.rtstruct.dcm");
  CommandResult r = runVesalius({"segment", "--scan", folder, "--modality", "ct", "--out", rt});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_EQ(runVesalius({"segment", "--scan", folder, "--modality", "ct", "--out", nifti}).exitCode, 0);
  EXPECT_FALSE(fs::exists(fs::path(rt).replace_extension(".tsv")));  // the structure set carries its names
  const SourceUids source = sourceUids(folder);
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(rt.c_str()).good());
  EXPECT_EQ(element(*file.getDataset(), DCM_Modality), "RTSTRUCT");
  EXPECT_EQ(element(*file.getDataset(), DCM_StudyInstanceUID), source.study);
  const LabelMap expected = io::readLabelMap(nifti);
  const LabelMap back = io::readDicomRtStruct(rt, expected.labels.geometry);
  std::size_t differing = 0;
  for (std::size_t n = 0; n < expected.labels.values.size(); ++n)
    differing += back.labels.values[n] != expected.labels.values[n];
  std::cout << "ct-3slice.rtstruct.dcm: " << fs::file_size(rt) << " bytes, " << back.table.entries.size()
            << " ROIs, " << differing << " voxels differ from the NIfTI\n";
  EXPECT_EQ(differing, 0u);

  // `labels` on the NIfTI, referring to the series named with --dicom-series.
  r = runVesalius({"labels", "extract", "--labels", nifti, "--label", "bone", "--out", bone, "--dicom-series", folder});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  DcmFileFormat boneFile;
  ASSERT_TRUE(boneFile.loadFile(bone.c_str()).good());
  DcmItem *frame = nullptr, *study = nullptr, *series = nullptr;
  ASSERT_TRUE(boneFile.getDataset()->findAndGetSequenceItem(DCM_ReferencedFrameOfReferenceSequence, frame, 0).good());
  EXPECT_EQ(element(*frame, DCM_FrameOfReferenceUID), source.frameOfReference);
  ASSERT_TRUE(frame->findAndGetSequenceItem(DCM_RTReferencedStudySequence, study, 0).good());
  ASSERT_TRUE(study->findAndGetSequenceItem(DCM_RTReferencedSeriesSequence, series, 0).good());
  EXPECT_EQ(element(*series, DCM_SeriesInstanceUID), source.series);
  const LabelMap extracted = io::readDicomRtStruct(bone, expected.labels.geometry);
  ASSERT_EQ(extracted.table.entries.size(), 1u);
  EXPECT_EQ(extracted.table.entries.front().name, "bone");
}

// Voxels that differ between two maps on one grid, and the Dice overlap of each of `ids`, printed.
std::size_t compareLabels(const LabelMap& back, const LabelMap& expected, const std::vector<Label>& ids,
                          const std::string& name) {
  EXPECT_EQ(back.labels.geometry.size, expected.labels.geometry.size) << name;
  if (back.labels.values.size() != expected.labels.values.size()) return expected.labels.values.size();
  std::size_t differing = 0;
  for (std::size_t n = 0; n < expected.labels.values.size(); ++n)
    differing += back.labels.values[n] != expected.labels.values[n];
  std::cout << name << ": " << differing << " of " << expected.labels.values.size() << " voxels differ;";
  for (Label id : ids) {
    std::size_t a = 0, b = 0, both = 0;
    for (std::size_t n = 0; n < expected.labels.values.size(); ++n) {
      a += back.labels.values[n] == id;
      b += expected.labels.values[n] == id;
      both += back.labels.values[n] == id && expected.labels.values[n] == id;
    }
    const double dice = a + b == 0 ? 0.0 : 2.0 * double(both) / double(a + b);
    std::cout << " label " << id << ": " << b << " voxels, Dice " << dice << ";";
    EXPECT_GT(b, 0u) << name << " label " << id;
    EXPECT_EQ(dice, 1.0) << name << " label " << id;
  }
  std::cout << '\n';
  return differing;
}

// The 3-slice series segmented by `segment` as an RT Structure Set and as NIfTI, named `name` + extension.
struct Segmented {
  std::string rtStruct, nifti;
};

Segmented segmentedTwice(const std::string& name) {
  const Segmented s{fresh(name + ".rtstruct.dcm"), fresh(name + ".nii.gz")};
  for (const std::string& out : {s.rtStruct, s.nifti}) {
    const CommandResult r = runVesalius({"segment", "--scan", kCt3SliceFolder, "--out", out});
    EXPECT_EQ(r.exitCode, 0) << r.err;
  }
  return s;
}

TEST(CliDicomSeg, LabelsAndSurfaceReadAnRtStructOntoTheGrid) {
  // Read back onto the series' grid: the DICOM folder itself.
  const std::string& folder = kCt3SliceFolder;
  const auto [rt, nifti] = segmentedTwice("grid-in");
  const std::string back = fresh("grid-back.nii.gz"), seg = fresh("grid-bone.dcm");
  const LabelMap expected = io::readLabelMap(nifti);
  std::vector<Label> ids;
  for (const LabelEntry& e : expected.table.entries)
    if (std::count(expected.labels.values.begin(), expected.labels.values.end(), e.id)) ids.push_back(e.id);
  ASSERT_GE(ids.size(), 2u);
  std::vector<std::string> args{"labels", "extract", "--labels", rt, "--grid", folder, "--out", back};
  for (Label id : ids) args.insert(args.end(), {"--label", std::to_string(id)});
  CommandResult r = runVesalius(args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const LabelMap read = io::readLabelMap(back);
  EXPECT_EQ(compareLabels(read, expected, ids, "ct-3slice.rtstruct.dcm onto its series"), 0u);
  for (Label id : ids) EXPECT_EQ(read.table.find(id)->name, expected.table.find(id)->name);

  // Written as a SEG, it refers to the series --grid names.
  r = runVesalius({"labels", "extract", "--labels", rt, "--grid", folder, "--label", "bone", "--out", seg});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const io::DicomSegmentation bone = io::readDicomSeg(seg);
  ASSERT_TRUE(bone.source);
  EXPECT_EQ(bone.source->seriesInstanceUid, sourceUids(folder).series);

  // `surface` of the structure set read onto a NIfTI grid makes the mesh the NIfTI's labels make.
  const std::string fromRt = fresh("grid-bone-rt.stl"), fromNifti = fresh("grid-bone-nifti.stl");
  r = runVesalius({"surface", "--labels", rt, "--grid", nifti, "--label", "bone", "--out", fromRt});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_EQ(runVesalius({"surface", "--labels", nifti, "--label", "bone", "--out", fromNifti}).exitCode, 0);
  const TriMesh a = io::readTriMesh(fromRt), b = io::readTriMesh(fromNifti);
  ASSERT_EQ(a.V.rows(), b.V.rows());
  ASSERT_EQ(a.F.rows(), b.F.rows());
  const double apart = (a.V - b.V).cwiseAbs().maxCoeff();
  std::cout << "bone surface: " << a.V.rows() << " vertices, " << a.F.rows()
            << " triangles; vertices differ by at most " << apart << " mm from the NIfTI's\n";
  EXPECT_EQ(apart, 0.0);
  EXPECT_EQ(a.F, b.F);
}

TEST(CliDicomSeg, OrgansOfTheShippedCtRoundTripThroughAnRtStruct) {
  // Liver, spleen and left kidney of the shipped CT's labels written by `labels extract` and read back onto
  // the CT's grid by it.
  const std::string rt = fresh("organs.rtstruct.dcm"), back = fresh("organs-back.nii.gz");
  const std::vector<std::string> organs{"--label", "liver", "--label", "spleen", "--label", "kidney_left"};
  std::vector<std::string> args{"labels", "extract", "--labels", kCtLabels, "--table", kCtLabelTable};
  args.insert(args.end(), organs.begin(), organs.end());
  args.insert(args.end(), {"--out", rt});
  CommandResult r = runVesalius(args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  args = {"labels", "extract", "--labels", rt, "--grid", kCtScan};
  args.insert(args.end(), organs.begin(), organs.end());
  args.insert(args.end(), {"--out", back});
  r = runVesalius(args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out;
  const LabelMap all = io::readLabelMap(kCtLabels, kCtLabelTable);
  std::vector<Label> ids;
  for (const char* organ : {"liver", "spleen", "kidney_left"}) ids.push_back(all.table.resolve(organ));
  LabelMap expected = all;
  for (Label& v : expected.labels.values)
    if (std::find(ids.begin(), ids.end(), v) == ids.end()) v = 0;
  const LabelMap read = io::readLabelMap(back);
  EXPECT_EQ(compareLabels(read, expected, ids, "organs.rtstruct.dcm onto example_ct.nii.gz"), 0u);
  for (Label id : ids) EXPECT_EQ(read.table.find(id)->name, all.table.find(id)->name);
}

TEST(CliDicomSeg, AnRtStructWithoutGridIsOneLineAndGridIsOnlyForOne) {
  const std::string& folder = kCt3SliceFolder;
  const auto [rt, nifti] = segmentedTwice("no-grid");
  const std::string out = fresh("no-grid-out.nii.gz"), mesh = fresh("no-grid.stl");
  // Named for its content only: found by its SOP class.
  const std::string renamed = fresh("no-grid-structures.dcm");
  fs::copy_file(rt, renamed);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"labels", "extract", "--labels", rt, "--label", "bone", "--out", out},
        std::vector<std::string>{"surface", "--labels", rt, "--label", "bone", "--out", mesh},
        std::vector<std::string>{"labels", "extract", "--labels", renamed, "--label", "bone", "--out", out}}) {
    const CommandResult r = runVesalius(args);
    std::cout << r.err;
    EXPECT_EQ(r.exitCode, 2) << args[0];
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    const std::string& labels = *(std::find(args.begin(), args.end(), "--labels") + 1);
    expectContains(r.err, labels + ": an RT Structure Set");
    expectContains(r.err, "pass --grid");
  }
  // --grid with a map on a grid of its own is a usage error, as is --grid without --labels.
  CommandResult r =
      runVesalius({"labels", "extract", "--labels", nifti, "--grid", folder, "--label", "bone", "--out", out});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 2) << r.err;
  expectContains(r.err, nifti);
  r = runVesalius({"tetmesh", "--surface", mesh, "--grid", folder, "--out", fresh("no-grid.vtu")});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 2) << r.err;
  expectContains(r.err, "--labels");
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(mesh));
}

// An RT Structure Set as PACS exports it, with no extension: found by its content, read onto the series
// --grid names, refused without --grid; onto a series of another frame of reference (TotalSegmentator's
// JPEG 2000 series for one written on dcmqi's) refused in one line naming both, exit 3 (bad input).
TEST(CliDicomSeg, AnRtStructWithoutExtensionIsFoundAndAnotherFrameIsRefused) {
  const Image scan = io::readScan(kCt3SliceFolder);
  const LabelMap map = softTissueAndBone(scan);
  const std::optional<io::DicomSourceSeries> source = io::readDicomSource(kCt3SliceFolder);
  ASSERT_TRUE(source);
  const std::string written = fresh("pacs.rtstruct.dcm"), rt = fresh("RS000001"), back = fresh("pacs-back.nii.gz");
  io::writeDicomRtStruct(written, map, &*source);
  fs::copy_file(written, rt);
  CommandResult r = runVesalius({"labels", "extract", "--labels", rt, "--grid", kCt3SliceFolder, "--label",
                                 "soft_tissue", "--label", "bone", "--out", back});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_EQ(compareLabels(io::readLabelMap(back), map, {1, 2}, "RS000001 onto its series"), 0u);

  r = runVesalius({"labels", "extract", "--labels", rt, "--label", "bone", "--out", fresh("pacs-no-grid.nii.gz")});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 2) << r.err;
  expectContains(r.err, rt + ": an RT Structure Set");

  const std::string other = kData + "/dicom/ct-series-jpeg2000";
  r = runVesalius({"labels", "extract", "--labels", rt, "--grid", other, "--label", "bone", "--out",
                   fresh("pacs-other.nii.gz")});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  expectContains(r.err, rt + ": ");
  expectContains(r.err, other);
  expectContains(r.err, "Frame of Reference " + source->frameOfReferenceUid);
  EXPECT_FALSE(fs::exists(fresh("pacs-other.nii.gz")));
}

// The commands that read a label map under another option than --labels, or without the shared option
// until now, read an RT Structure Set onto the --grid scan as the same map in NIfTI: `reference torso`
// makes the same reference of the shipped CT's 30-slice labels, `pose` the same posed labels.
TEST(CliDicomSeg, ReferenceTorsoReadsAnRtStructOntoTheGrid) {
  const std::string dir = kData + "/ct-abdomen-pelvis/";
  const std::string ct = dir + "example_ct_sm.nii.gz", labels = dir + "example_seg.nii.gz",
                    table = dir + "labels_total_v2.tsv";
  const std::string rt = fresh("torso.rtstruct.dcm"), fromRt = freshFolder("torso-rt"),
                    fromNifti = freshFolder("torso-nifti");
  io::writeDicomRtStruct(rt, io::readLabelMap(labels, table), nullptr);
  const CommandResult a = runVesalius({"reference", "torso", "--scan", ct, "--labels", rt, "--grid", ct,
                                       "--label-table", table, "--out", fromRt, "--progress", "none"});
  ASSERT_EQ(a.exitCode, 0) << a.err;
  const CommandResult b = runVesalius({"reference", "torso", "--scan", ct, "--labels", labels, "--label-table", table,
                                       "--out", fromNifti, "--progress", "none"});
  ASSERT_EQ(b.exitCode, 0) << b.err;
  std::cout << a.out << b.out;
  EXPECT_EQ(a.out.substr(fromRt.size()), b.out.substr(fromNifti.size()));
}

TEST(CliDicomSeg, PoseReadsAnRtStructOntoTheGrid) {
  const std::string rig = freshFolder("pose-rig"), fromRt = freshFolder("pose-rt"),
                    fromNifti = freshFolder("pose-nifti");
  CommandResult r = runVesalius({"rig", "--skin", kData + "/body/shapes/mh_neutral_body.obj", "--skeleton",
                                 kData + "/body/default.mhskel", "--voxel-size", "8", "--target-tets", "8000",
                                 "--no-cor-centres", "--out", rig, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // The 3-slice CT's two classes, as a label map in the rig's space.
  const LabelMap map = softTissueAndBone(io::readScan(kCt3SliceFolder));
  const std::string rt = fresh("pose.rtstruct.dcm"), nifti = fresh("pose.nii.gz");
  io::writeDicomRtStruct(rt, map, nullptr);
  io::writeLabelMap(nifti, map);
  const std::vector<std::string> pose{"pose", "--anatomy", rig, "--angles", "upperleg01.L=-30,0,0", "--progress", "none"};
  std::vector<std::string> args = pose;
  // Onto the NIfTI: written without a source series, the structure set has a frame of reference of its own.
  args.insert(args.end(), {"--labels", rt, "--grid", nifti, "--out", fromRt});
  r = runVesalius(args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  args = pose;
  args.insert(args.end(), {"--labels", nifti, "--out", fromNifti});
  ASSERT_EQ(runVesalius(args).exitCode, 0);
  // The posed copy keeps the input's name, and so its format.
  const LabelMap posedNifti = io::readLabelMap(fromNifti + "/pose.nii.gz");
  const LabelMap posedRt = io::readDicomRtStruct(fromRt + "/pose.rtstruct.dcm", posedNifti.labels.geometry);
  EXPECT_EQ(compareLabels(posedRt, posedNifti, {1, 2}, "posed pose.rtstruct.dcm"), 0u);
  // Found by its content under a PACS name: written back under that name as an RT Structure Set.
  const std::string pacs = freshFolder("pose-pacs") + "/RS000001", fromPacs = freshFolder("pose-rt-pacs");
  fs::create_directories(fs::path(pacs).parent_path());
  fs::copy_file(rt, pacs);
  args = pose;
  args.insert(args.end(), {"--labels", pacs, "--grid", nifti, "--out", fromPacs});
  r = runVesalius(args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const LabelMap posedPacs = io::readDicomRtStruct(fromPacs + "/RS000001.rtstruct.dcm", posedNifti.labels.geometry);
  EXPECT_EQ(compareLabels(posedPacs, posedNifti, {1, 2}, "posed RS000001.rtstruct.dcm"), 0u);
  // Without --grid, refused before the rig is embedded.
  args = pose;
  args.insert(args.end(), {"--labels", rt, "--out", freshFolder("pose-no-grid")});
  r = runVesalius(args);
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 2) << r.err;
  expectContains(r.err, "pass --grid");
}

// `reference organs` and `patient` take --organs as an RT Structure Set with --grid. Their whole runs take
// minutes, so the tests stop at a refusal that comes after the organs are read: an empty --reference folder
// for `reference organs`; for `patient`, a table naming no organ, refused as for the same map in NIfTI (the
// table replaces the ROIs' names). Without --grid the structure set is refused (exit 2).
TEST(CliDicomSeg, ReferenceOrgansAndPatientReadAnRtStructOntoTheGrid) {
  const std::string dir = kData + "/ct-abdomen-pelvis/";
  const std::string ct = dir + "example_ct_sm.nii.gz", labels = dir + "example_seg.nii.gz",
                    table = dir + "labels_total_v2.tsv";
  const std::string rt = fresh("organs-sm.rtstruct.dcm"), unknown = fresh("organs-unknown.tsv");
  io::writeDicomRtStruct(rt, io::readLabelMap(labels, table), nullptr);
  {
    std::ofstream t(unknown);
    t << "label\tname\n";
    for (int id = 1; id <= 200; ++id) t << id << "\tstructure_" << id << "\n";
  }
  const std::string empty = freshFolder("not-a-reference"), out = freshFolder("organs-out");
  fs::create_directories(empty);

  CommandResult r = runVesalius({"reference", "organs", "--scan", ct, "--organs", rt, "--grid", ct, "--organ-table",
                                 table, "--reference", empty, "--out", out, "--progress", "none"});
  std::cout << r.err;
  EXPECT_EQ(r.exitCode, 3) << r.err;
  expectContains(r.err, empty);
  EXPECT_EQ(r.err.find(rt), std::string::npos) << r.err;

  r = runVesalius({"patient", "--scan", ct, "--organs", rt, "--grid", ct, "--organ-table", unknown, "--out", out,
                   "--progress", "none"});
  const CommandResult nifti = runVesalius(
      {"patient", "--scan", ct, "--organs", labels, "--organ-table", unknown, "--out", out, "--progress", "none"});
  std::cout << r.err << nifti.err;
  EXPECT_EQ(r.exitCode, 3) << r.err;
  EXPECT_EQ(nifti.exitCode, 3) << nifti.err;
  ASSERT_EQ(r.err.rfind("vesalius: " + rt + ": ", 0), 0u) << r.err;
  ASSERT_EQ(nifti.err.rfind("vesalius: " + labels + ": ", 0), 0u) << nifti.err;
  EXPECT_EQ(r.err.substr(std::string("vesalius: ").size() + rt.size()),
            nifti.err.substr(std::string("vesalius: ").size() + labels.size()));

  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"reference", "organs", "--scan", ct, "--organs", rt, "--out", out},
        std::vector<std::string>{"patient", "--scan", ct, "--organs", rt, "--out", out}}) {
    r = runVesalius(args);
    std::cout << r.err;
    EXPECT_EQ(r.exitCode, 2) << args[0];
    expectContains(r.err, rt + ": an RT Structure Set");
  }
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace vesalius::test
