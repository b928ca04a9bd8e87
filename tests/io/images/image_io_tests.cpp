// Scans and label maps on real files: sizes, spacings, values and orientation as shipped, round trips in
// every writable format, DICOM series, and one-line BadInput errors for broken inputs (testdata/bad/).
#include "vesalius/io/image_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/dicom_series.h"
#include "vesalius/io/label_table_io.h"

#include "expect_bad_input.h"
#include "test_data.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>

namespace vesalius::io {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
const std::string kHeadMri = kData + "/head-mri/ch2.nii.gz";
using test::kCtLabels;
using test::kCtLabelTable;
using test::kCtScan;
const std::string kObliqueCt = kData + "/oblique-ct/CT_pitch.nii.gz";
const std::string kJpeg2000Series = kData + "/dicom/ct-series-jpeg2000";
const std::string kThreeSlices = kData + "/dicom/ct-3slice-dcmqi/ct-3slice";
const std::string kSingleDicom = kData + "/dicom/pydicom/CT_small.dcm";
const std::string kBad = kData + "/bad";

// An empty folder under the test output, one per test.
fs::path freshOutputFolder(const std::string& name) {
  const fs::path folder = fs::path(VESALIUS_TEST_OUTPUT) / name;
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

std::vector<std::string> folderEntries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  return names;
}

double mean(const std::vector<float>& values) {
  return std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
}

void expectSameGeometry(const GridGeometry& a, const GridGeometry& b) {
  EXPECT_EQ(a.size, b.size);
  EXPECT_LT((a.spacing - b.spacing).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((a.origin - b.origin).cwiseAbs().maxCoeff(), 1e-4);
  EXPECT_LT((a.direction - b.direction).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(ImageIo, HeadMriIsUint8At1mm) {
  const Image image = readScan(kHeadMri);
  EXPECT_EQ(image.geometry.size, Eigen::Vector3i(181, 217, 181));
  EXPECT_TRUE(image.geometry.spacing.isApprox(Eigen::Vector3d(1, 1, 1), 1e-9));
  EXPECT_EQ(image.fileType, PixelType::UInt8);
  EXPECT_EQ(image.values.size(), std::size_t(181 * 217 * 181));
}

TEST(ImageIo, AbdomenCtIsInt32HounsfieldAt3mm) {
  const Image image = readScan(kCtScan);
  EXPECT_EQ(image.geometry.size, Eigen::Vector3i(122, 101, 112));
  EXPECT_TRUE(image.geometry.spacing.isApprox(Eigen::Vector3d(3, 3, 3), 1e-6));
  EXPECT_EQ(image.fileType, PixelType::Int32);
  const auto [low, high] = std::minmax_element(image.values.begin(), image.values.end());
  EXPECT_EQ(*low, -1207.0f);
  EXPECT_EQ(*high, 3382.0f);
  // The NIfTI affine is diag(3, 3, 3) in RAS: i runs to the patient's right, j anterior, k superior. ITK
  // turns it into LPS physical space, where those axes read as direction diag(-1, -1, 1), code "RAS".
  EXPECT_TRUE(
      image.geometry.direction.isApprox(Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix(), 1e-9));
  EXPECT_TRUE(image.geometry.origin.isApprox(Eigen::Vector3d(177.9563, -11.3190, 94.3018), 1e-5));
  EXPECT_EQ(image.geometry.orientationCode(), "RAS");
}

TEST(ImageIo, DescribeScanGivesHeaderAndValueRange) {
  const ScanInfo info = describeScan(kCtScan);
  EXPECT_EQ(info.format, "NIfTI");
  EXPECT_EQ(info.geometry.size, Eigen::Vector3i(122, 101, 112));
  EXPECT_EQ(info.pixelType, PixelType::Int32);
  EXPECT_EQ(info.components, 1);
  EXPECT_EQ(info.orientation, "RAS");
  ASSERT_TRUE(info.valueRange.has_value());
  EXPECT_EQ(info.valueRange->minimum, -1207.0);
  EXPECT_EQ(info.valueRange->maximum, 3382.0);
}

class ImageRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(ImageRoundTrip, KeepsGeometryValuesAndStoredType) {
  const fs::path folder = freshOutputFolder("round_trip" + std::string(GetParam()).replace(0, 1, "_"));
  const std::string path = (folder / ("ct" + GetParam())).string();
  const Image original = readScan(kCtScan);
  writeScan(path, original);
  const Image copy = readScan(path);
  expectSameGeometry(copy.geometry, original.geometry);
  EXPECT_EQ(copy.fileType, original.fileType);
  EXPECT_TRUE(copy.values == original.values);
  for (const std::string& name : folderEntries(folder))
    EXPECT_NE(name.front(), '.') << "left behind: " << name;
}

INSTANTIATE_TEST_SUITE_P(EveryWritableFormat, ImageRoundTrip,
                         ::testing::Values(".nii", ".nii.gz", ".nrrd", ".nhdr", ".mha", ".mhd"),
                         [](const auto& info) {
                           return info.param.substr(1) == "nii.gz" ? std::string("nii_gz")
                                                                   : info.param.substr(1);
                         });

TEST(ImageIo, DetachedHeaderAndDataFileGetFinalNames) {
  const fs::path folder = freshOutputFolder("detached_names");
  const Image original = readScan(kCtScan);
  writeScan((folder / "ct.nhdr").string(), original);
  writeScan((folder / "ct.mhd").string(), original);
  EXPECT_EQ(folderEntries(folder), (std::vector<std::string>{"ct.mhd", "ct.nhdr", "ct.raw.gz", "ct.zraw"}));
}

TEST(ImageIo, ObliqueDirectionSurvivesRoundTrip) {
  const Image original = readScan(kObliqueCt);
  const Eigen::Matrix3d& direction = original.geometry.direction;
  EXPECT_GT((direction - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 0.1)
      << "test scan should be tilted";
  EXPECT_LT((direction.transpose() * direction - Eigen::Matrix3d::Identity()).norm(), 1e-5);
  for (const std::string extension : {".nii.gz", ".nrrd", ".mha"}) {
    const fs::path folder = freshOutputFolder("oblique");
    const std::string path = (folder / ("pitch" + extension)).string();
    writeScan(path, original);
    const Image copy = readScan(path);
    EXPECT_LT((copy.geometry.direction - direction).cwiseAbs().maxCoeff(), 1e-6) << extension;
    EXPECT_LT((copy.geometry.origin - original.geometry.origin).cwiseAbs().maxCoeff(), 1e-4) << extension;
    EXPECT_TRUE(copy.values == original.values) << extension;
  }
}

TEST(ImageIo, ExistingOutputIsKeptUnlessForced) {
  const fs::path folder = freshOutputFolder("no_clobber");
  const std::string path = (folder / "ct.nii.gz").string();
  Image image = readScan(kCtScan);
  writeScan(path, image);
  const auto written = fs::last_write_time(path);
  image.values.assign(image.values.size(), 0.0f);
  EXPECT_THROW(writeScan(path, image), UsageError);
  EXPECT_EQ(fs::last_write_time(path), written);
  writeScan(path, image, WriteOptions{true});
  EXPECT_EQ(readScan(path).values.front(), 0.0f);
}

TEST(ImageIo, FailedWriteLeavesNoFile) {
  const fs::path folder = freshOutputFolder("failed_write");
  Image empty;  // size 0x0x0: ITK refuses to write it
  EXPECT_THROW(writeScan((folder / "empty.nii.gz").string(), empty), BadInput);
  EXPECT_TRUE(folderEntries(folder).empty());
}

TEST(ImageIo, UnknownOutputExtensionIsAUsageError) {
  const fs::path folder = freshOutputFolder("bad_output_extension");
  EXPECT_THROW(writeScan((folder / "ct.png").string(), readScan(kCtScan)), UsageError);
}

TEST(ImageIo, Jpeg2000DicomSeriesDecodes) {
  const Image image = readScan(kJpeg2000Series);
  EXPECT_EQ(image.geometry.size, Eigen::Vector3i(512, 512, 20));
  EXPECT_NEAR(image.geometry.spacing.x(), 0.977, 1e-3);
  EXPECT_NEAR(image.geometry.spacing.y(), 0.977, 1e-3);
  EXPECT_NEAR(image.geometry.spacing.z(), 2.0, 1e-6);
  EXPECT_NEAR(mean(image.values), -624.0, 1.0);
  EXPECT_EQ(image.fileType, PixelType::Int16);
}

TEST(ImageIo, ThreeSliceSeriesIsSortedByPosition) {
  const Image image = readScan(kThreeSlices);
  EXPECT_EQ(image.geometry.size, Eigen::Vector3i(512, 512, 3));
  EXPECT_GT(image.geometry.spacing.z(), 0.0);
  ASSERT_EQ(listDicomSeries(kThreeSlices).size(), 1u);
  EXPECT_EQ(listDicomSeries(kThreeSlices).front().sliceCount, 3);
}

TEST(ImageIo, SingleDicomFileReads) {
  const Image image = readScan(kSingleDicom);
  EXPECT_EQ(image.geometry.size, Eigen::Vector3i(128, 128, 1));
  const ScanInfo info = describeScan(kSingleDicom);
  EXPECT_EQ(info.format, "DICOM file");
}

TEST(ImageIo, SeriesUidPicksOneSeriesOfAMixedFolder) {
  const std::string folder = kBad + "/dicom_two_series";
  const std::vector<DicomSeries> series = listDicomSeries(folder);
  ASSERT_EQ(series.size(), 2u);
  for (const DicomSeries& s : series) {
    ScanReadOptions options;
    options.seriesUid = s.uid;
    EXPECT_EQ(readScan(folder, options).geometry.size.z(), s.sliceCount);
  }
  ScanReadOptions unknown;
  unknown.seriesUid = "1.2.3.4";
  EXPECT_THROW(readScan(folder, unknown), UsageError);
}

TEST(ImageIo, TotalSegmentatorV1LabelMapConvertsFromFloat64) {
  const LabelMap labelMap = readLabelMap(kCtLabels, kCtLabelTable);
  EXPECT_EQ(labelMap.labels.geometry.size, Eigen::Vector3i(122, 101, 112));
  const auto count = [&](Label id) {
    return std::count(labelMap.labels.values.begin(), labelMap.labels.values.end(), id);
  };
  EXPECT_EQ(count(5), 41602);  // liver voxels, 27 ml each: 1.12 l
  EXPECT_GT(count(88), 0);
  EXPECT_GT(count(89), 0);
  ASSERT_NE(labelMap.table.find("liver"), nullptr);
  EXPECT_EQ(labelMap.table.find("liver")->id, 5);
  EXPECT_EQ(labelMap.table.find(88)->name, "femur_left");
  expectSameGeometry(labelMap.labels.geometry, readScan(kCtScan).geometry);
}

TEST(ImageIo, TotalSegmentatorTablesRead) {
  const LabelTable table = readLabelTable(kCtLabelTable);
  EXPECT_EQ(table.entries.size(), 104u);
  EXPECT_EQ(table.resolve("liver"), 5);
  EXPECT_EQ(readLabelTable(kData + "/ct-abdomen-pelvis/labels_tissue_types.tsv").entries.size(), 3u);
}

TEST(ImageIo, LabelMapWithoutTableNamesLabelsById) {
  const LabelMap labelMap = readLabelMap(kCtLabels);
  ASSERT_NE(labelMap.table.find(5), nullptr);
  EXPECT_EQ(labelMap.table.find(5)->name, "label_5");
  EXPECT_EQ(labelMap.table.find(5)->color, defaultLabelColor(5));
}

TEST(ImageIo, LabelMapRoundTripWritesSidecarTable) {
  const fs::path folder = freshOutputFolder("label_round_trip");
  const LabelMap original = readLabelMap(kCtLabels, kCtLabelTable);
  const std::string path = (folder / "seg.nii.gz").string();
  writeLabelMap(path, original);
  EXPECT_EQ(labelTableSidecarPath(path), (folder / "seg.tsv").string());
  EXPECT_EQ(describeScan(path).pixelType, PixelType::UInt8);
  const LabelMap copy = readLabelMap(path);  // finds seg.tsv by itself
  EXPECT_TRUE(copy.labels.values == original.labels.values);
  EXPECT_EQ(copy.table.find(5)->name, "liver");
  EXPECT_EQ(copy.table.entries.size(), original.table.entries.size());
  EXPECT_THROW(writeLabelMap(path, original), UsageError);
}

TEST(ImageIo, LargeLabelIdsAreStoredAsUint16) {
  const fs::path folder = freshOutputFolder("label_uint16");
  LabelMap labelMap;
  GridGeometry geometry;
  geometry.size = Eigen::Vector3i(4, 3, 2);
  labelMap.labels = Grid<Label>(geometry, 0);
  labelMap.labels.at(1, 2, 1) = 300;
  const std::string path = (folder / "big.nrrd").string();
  writeLabelMap(path, labelMap);
  EXPECT_EQ(describeScan(path).pixelType, PixelType::UInt16);
  EXPECT_EQ(readLabelMap(path).labels.at(1, 2, 1), 300);
}

TEST(ImageIo, FractionalLabelValueIsBadInput) {
  const fs::path folder = freshOutputFolder("label_fraction");
  GridGeometry geometry;
  geometry.size = Eigen::Vector3i(2, 2, 2);
  Image image(geometry, 1.0f);
  image.at(1, 0, 1) = 2.5f;
  image.fileType = PixelType::Float32;
  const std::string path = (folder / "fraction.mha").string();
  writeScan(path, image);
  try {
    readLabelMap(path);
    ADD_FAILURE() << "a label of 2.5 was accepted";
  } catch (const BadInput& error) {
    EXPECT_NE(std::string(error.what()).find("voxel (1, 0, 1) holds 2.5"), std::string::npos) << error.what();
  }
}

// Each broken input throws BadInput with a one-line message that names it.
void expectOneLineBadInput(const std::string& path, const std::string& fragment) {
  test::expectOneLineBadInput(path, fragment, [&] { readScan(path); });
}

TEST(ImageIo, BrokenInputsAreOneLineBadInput) {
  expectOneLineBadInput(kBad + "/scan_truncated.nii.gz", "truncated");
  expectOneLineBadInput(kBad + "/scan_zero_spacing.nii", "spacing");
  expectOneLineBadInput(kBad + "/dicom_two_series", "2 DICOM series");
  expectOneLineBadInput(kBad + "/scan_missing.nii.gz", "no such file");
  expectOneLineBadInput(kBad + "/scan_unknown_extension.xyz", "unknown scan format '.xyz'");
  // Found by fuzz_nifti and fuzz_mha: a 390-byte .nii without the "n+1" magic whose header declares 3 GB
  // of int64 voxels (nifticlib reads it from the same file all the same), and a MetaImage whose data file
  // is a numbered pattern over 16 GB (MetaIO allocates it all, then divides by zero), or empty.
  expectOneLineBadInput(kBad + "/scan_nifti_no_magic_3gb.nii", "file is truncated: 390 of 3221225472 bytes");
  expectOneLineBadInput(kBad + "/scan_mha_pattern_16gb.mha", "MetaImage data split over several files");
  expectOneLineBadInput(kBad + "/scan_mha_empty_data_file.mha", "ElementDataFile is empty");
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// A NRRD or MetaImage header declaring 2000 x 2000 x 1000 shorts (8 GB) over a few hundred bytes: ITK would
// allocate them all before reading; refused first, for every encoding and for attached and detached data
// (fuzz_nrrd and fuzz_mha found these). The same volume really stored is read.
TEST(ImageIo, HeadersDeclaringMoreVoxelsThanTheirDataHoldsAreRefused) {
  const fs::path folder = freshOutputFolder("memory_bombs");
  const std::string nrrd = "NRRD0004\ntype: short\ndimension: 3\nspace: left-posterior-superior\n"
                           "sizes: 2000 2000 1000\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nendian: little\n";
  const std::string mha = "ObjectType = Image\nNDims = 3\nBinaryData = True\nElementSpacing = 1 1 1\n"
                          "DimSize = 2000 2000 1000\nElementType = MET_SHORT\n";
  const std::string data(600, '\0');
  const std::pair<std::string, std::string> files[] = {
      {"raw.nrrd", nrrd + "encoding: raw\n\n" + data},
      {"gzip.nrrd", nrrd + "encoding: gzip\n\n" + data},
      {"ascii.nrrd", nrrd + "encoding: ascii\n\n1 2 3 4\n"},
      {"detached.nhdr", nrrd + "encoding: gzip\ndata file: detached.raw.gz\n\n"},
      {"compressed.mha", mha + "CompressedData = True\nElementDataFile = LOCAL\n" + data},
      {"compressed_sized.mha", mha + "CompressedData = True\nCompressedDataSize = 600\nElementDataFile = LOCAL\n" + data},
      {"detached.mhd", mha + "CompressedData = True\nElementDataFile = detached.zraw\n"},
      {"overflow.mha", "ObjectType = Image\nNDims = 3\nBinaryData = True\nCompressedData = True\n"
                       "DimSize = 2147483647 2147483647 2147483647\nElementType = MET_DOUBLE\nElementDataFile = LOCAL\n" + data},
  };
  writeBytes(folder / "detached.raw.gz", data);
  writeBytes(folder / "detached.zraw", data);
  for (const auto& [name, bytes] : files) {
    writeBytes(folder / name, bytes);
    const std::string path = (folder / name).string();
    std::string message;
    try {
      readScan(path);
    } catch (const BadInput& e) {
      message = e.what();
    }
    std::cout << name << ": " << message << "\n";
    EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
    EXPECT_TRUE(message.find("bytes of data stored can hold") != std::string::npos ||
                message.find("more voxels than 64 bits can count") != std::string::npos)
        << message;
  }
  // What the check lets through: the volume written by us (gzip-compressed, ratio far below 1032).
  Image image;
  image.geometry.size = {64, 64, 32};
  image.values.assign(std::size_t(image.geometry.voxelCount()), 0.0f);
  image.fileType = PixelType::Int16;
  for (const std::string extension : {".nrrd", ".mha", ".nhdr", ".mhd"}) {
    const std::string path = (folder / ("zeros" + extension)).string();
    writeScan(path, image);
    EXPECT_EQ(readScan(path).values.size(), image.values.size()) << path;
  }
}

// MetaImage dimensions that disagree: MetaIO reads as many voxels as DimSize says into the image ITK made
// from NDims (NDims = 0 over DimSize = 4 3 2, found by fuzz_mha, overflows its buffer).
TEST(ImageIo, MetaImageDimSizeMustHoldNDimsPositiveWholeNumbers) {
  const fs::path folder = freshOutputFolder("metaimage_dimensions");
  const std::pair<std::string, std::string> cases[] = {
      {"NDims = 0\nDimSize = 4 3 2\n", "NDims is '0'"},
      {"NDims = 3\nDimSize = 4 3\n", "DimSize holds 2 numbers but NDims is 3"},
      {"NDims = 3\nDimSize = 4 0 2\n", "DimSize holds 0"},
      {"NDims = 3\nDimSize = 4 3 2.5\n", "DimSize holds 2.5"},
      {"NDims = 2.5\nDimSize = 4 3 2\n", "NDims is '2.5'"},
      {"DimSize = 4 3 2\n", "without NDims or DimSize"},
  };
  int n = 0;
  for (const auto& [dimensions, fragment] : cases) {
    const fs::path path = folder / ("case" + std::to_string(n++) + ".mha");
    writeBytes(path, "ObjectType = Image\n" + dimensions +
                         "BinaryData = True\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n" + std::string(24, '\1'));
    test::expectOneLineBadInput(path.string(), fragment, [&] { readScan(path.string()); });
  }
}

// ITK's MetaIO reads a compressed stream that is corrupt or short as a whole image (zeros where inflating
// stopped) and, without CompressedDataSize, inflates a LOCAL file from its header; it keeps its own choice
// of a repeated key and reads a header's numbers only up to a NUL byte (fuzz_mha: a bad free in MetaIO).
// Each is one line naming the file; the file as written reads.
TEST(ImageIo, CompressedMetaImageMustInflateToItsVoxelsAndItsHeaderBeText) {
  const fs::path folder = freshOutputFolder("metaimage_compressed");
  Image image;
  image.geometry.size = {40, 30, 20};
  image.fileType = PixelType::Int16;
  image.values.resize(std::size_t(image.geometry.voxelCount()));
  for (std::size_t n = 0; n < image.values.size(); ++n) image.values[n] = float((n * 7919) % 2001) - 1000;
  const std::string written = (folder / "written.mha").string();
  writeScan(written, image);
  const Image back = readScan(written);
  EXPECT_EQ(back.values, image.values);

  std::ifstream in(written, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string dataLine = "ElementDataFile = LOCAL\n";
  const std::size_t dataAt = bytes.find(dataLine) + dataLine.size();
  ASSERT_NE(bytes.find("CompressedDataSize"), std::string::npos);
  const std::string header = bytes.substr(0, dataAt), data = bytes.substr(dataAt);
  ASSERT_GT(data.size(), 1000u);

  std::string flipped = data;
  flipped[flipped.size() / 2] = char(~flipped[flipped.size() / 2]);
  std::string unsized = header;
  unsized.erase(unsized.find("CompressedDataSize"), unsized.find('\n', unsized.find("CompressedDataSize")) -
                                                        unsized.find("CompressedDataSize") + 1);
  std::string twice = header;
  twice.insert(0, "NDims = 2\n");
  std::string nul = header;
  nul.insert(nul.find("DimSize = ") + 12, std::string(1, '\0'));
  // Found by fuzz_mha: MetaIO reads a line without '=' as a key whose value is on the next line.
  std::string bare = header;
  bare.insert(bare.find("DimSize = "), "NDims\n");
  std::string spaced = header;
  spaced.insert(spaced.find("DimSize = "), "Binary Data = True\n");
  // MetaIO takes "CompressedData = Tr..." for True and skips '=' and ':' before a value.
  std::string loose = header;
  loose.replace(loose.find("CompressedData = True"), 21, "CompressedData = Truen");
  loose.replace(loose.find("CompressedDataSize = "), 21, "CompressedDataSize =: ");
  std::string typeSuffix = header;
  typeSuffix.insert(typeSuffix.find("MET_SHORT") + 9, "\xef\xff");
  std::string longKey = header;
  longKey.insert(longKey.find("DimSize = "), std::string(300, 'K') + " = 1\n");
  std::string longValue = header;
  longValue.insert(longValue.find("DimSize = "), "Comment = " + std::string(300, 'c') + "\n");
  const std::pair<std::string, std::string> cases[] = {
      {header + flipped, "compressed data is corrupt"},
      {header + data.substr(0, data.size() - 10), "data is cut short"},
      {unsized + data, "compressed data without CompressedDataSize"},
      {twice + data, "gives NDims twice"},
      {nul + data, "holds the control byte 0"},
      {bare + data, "is not 'Key = Value'"},
      {spaced + data, "is not 'Key = Value'"},
      {loose + flipped, "compressed data is corrupt"},
      {typeSuffix + data, "is not one of MET_CHAR"},
      {longKey + data, "a key of 300 characters"},
      {longValue + data, "a value of 300"},
  };
  int n = 0;
  for (const auto& [file, fragment] : cases) {
    const fs::path path = folder / ("case" + std::to_string(n++) + ".mha");
    writeBytes(path, file);
    test::expectOneLineBadInput(path.string(), fragment, [&] { readScan(path.string()); });
  }
}

// Found by fuzz_nrrd and fuzz_nifti: NrrdIO reads field names in any case, so "encOding: gzip" declaring
// 8 GB over a few bytes must meet the same check as "encoding: gzip"; an sform entry of -1.7e38 made VNL's
// SVD of ITK's orientation loop for ever. Each is one line naming the file.
TEST(ImageIo, NrrdFieldsInAnyCaseAndNiftiOrientationsBeyondAnyScanAreRefused) {
  const fs::path folder = freshOutputFolder("header_cases");
  const fs::path nrrd = folder / "mixed_case.nrrd";
  writeBytes(nrrd, "NRRD0004\ntype: short\ndimension: 3\nsizes: 2000 2000 1000\nEndian: little\nencOding: GZIP\n\n" +
                       std::string(600, '\0'));
  test::expectOneLineBadInput(nrrd.string(), "header declares 8000000000 bytes of voxels", [&] { readScan(nrrd.string()); });

  Image image;
  image.geometry.size = {4, 3, 2};
  image.values.assign(24, 1.0f);
  const fs::path nifti = folder / "huge_srow.nii";
  writeScan(nifti.string(), image);
  std::fstream file(nifti, std::ios::in | std::ios::out | std::ios::binary);
  const std::int16_t code = 1;
  const float huge = -1.7e38f;
  file.seekp(254);  // sform_code
  file.write(reinterpret_cast<const char*>(&code), sizeof code);
  file.seekp(284);  // srow_x[1]
  file.write(reinterpret_cast<const char*>(&huge), sizeof huge);
  file.close();
  test::expectOneLineBadInput(nifti.string(), "the orientation field srow_x[1] is -1.7e+38, beyond", [&] { readScan(nifti.string()); });
}

// nifticlib takes a NIfTI-1 file's byte order from dim[0], not sizeof_hdr: a header with sizeof_hdr in
// little-endian order and everything else big-endian declares 2000 x 2000 x 1000 shorts to nifticlib, and
// must be refused as truncated before ITK allocates them (fuzz_nifti ran out of memory on one).
TEST(ImageIo, NiftiByteOrderIsTakenFromDim0AsNifticlibDoes) {
  const fs::path folder = freshOutputFolder("nifti_byte_order");
  std::string header(352, '\0');
  const auto putBig = [&](std::size_t at, auto value) {
    char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    std::reverse(bytes, bytes + sizeof value);
    std::memcpy(&header[at], bytes, sizeof value);
  };
  const std::int32_t size = 348;
  std::memcpy(&header[0], &size, sizeof size);  // little-endian
  const std::int16_t dim[8] = {3, 2000, 2000, 1000, 1, 1, 1, 1};
  for (int n = 0; n < 8; ++n) putBig(40 + 2 * std::size_t(n), dim[n]);
  putBig(70, std::int16_t(4));  // int16
  putBig(72, std::int16_t(16));
  for (int n = 0; n < 8; ++n) putBig(76 + 4 * std::size_t(n), 1.0f);
  putBig(108, 352.0f);
  std::memcpy(&header[344], "n+1", 4);
  const fs::path path = folder / "mixed_order.nii";
  writeBytes(path, header + std::string(600, '\0'));
  test::expectOneLineBadInput(path.string(), "file is truncated: 952 of 8000000352 bytes", [&] { readScan(path.string()); });
  // ITK takes a file with the magic "n+1" as NIfTI whatever its sizeof_hdr says (fuzz_nifti: "DI\0\0").
  header.replace(0, 4, std::string("DI\0\0", 4));
  const fs::path wrongSize = folder / "wrong_sizeof_hdr.nii";
  writeBytes(wrongSize, header + std::string(600, '\0'));
  test::expectOneLineBadInput(wrongSize.string(), "sizeof_hdr", [&] { readScan(wrongSize.string()); });
}

// A NIfTI header whose vox_offset and sizes make a byte count beyond 64 bits (fuzz_nifti): refused as
// truncated, not converted with undefined behaviour.
TEST(ImageIo, NiftiByteCountsBeyond64BitsAreTruncatedFiles) {
  const fs::path folder = freshOutputFolder("nifti_byte_counts");
  for (const float offset : {352.0f, 1e30f, 3e38f}) {
    std::string header(352, '\0');
    const auto put = [&](std::size_t at, auto value) { std::memcpy(&header[at], &value, sizeof value); };
    put(0, std::int32_t(348));
    const std::int16_t dim[8] = {3, 32767, 32767, 32767, 1, 1, 1, 1};
    std::memcpy(&header[40], dim, sizeof dim);
    put(70, std::int16_t(64));  // float64
    put(72, std::int16_t(64));
    const float pixdim[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    std::memcpy(&header[76], pixdim, sizeof pixdim);
    put(108, offset);
    std::memcpy(&header[344], "n+1", 4);
    const fs::path path = folder / ("offset_" + std::to_string(int(std::log10(offset))) + ".nii");
    writeBytes(path, header + std::string(64, '\0'));
    test::expectOneLineBadInput(path.string(), "truncated", [&] { readScan(path.string()); });
  }
}

}  // namespace
}  // namespace vesalius::io
