// Scans and label maps (image_io.h): format choice, geometry checks, label conversion, atomic writes.
// The ITK work happens behind the plain-data seam of image_io_itk.h; this file sees the system Eigen only.
#include "vesalius/io/image_io.h"

#include "image_io_itk.h"
#include "label_names.h"
#include "raw_geometry.h"

#include "vesalius/core/error.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/label_table_io.h"
#include "vesalius/io/slicer_segmentation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace vesalius::io {

namespace {

namespace fs = std::filesystem;
using itk_seam::StoredType;

enum class ScanFormat { Nifti, Nrrd, MetaImage, DicomFile, DicomFolder };

const char* formatName(ScanFormat format) {
  switch (format) {
    case ScanFormat::Nifti: return "NIfTI";
    case ScanFormat::Nrrd: return "NRRD";
    case ScanFormat::MetaImage: return "MetaImage";
    case ScanFormat::DicomFile: return "DICOM file";
    case ScanFormat::DicomFolder: return "DICOM series";
  }
  return "";
}

const char* const kKnownFormats =
    "expected .nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd, a DICOM file or a DICOM folder";

std::optional<ScanFormat> fileFormatOf(const std::string& extension) {
  if (extension == ".nii" || extension == ".nii.gz") return ScanFormat::Nifti;
  if (extension == ".nrrd" || extension == ".nhdr" || extension == ".seg.nrrd") return ScanFormat::Nrrd;
  if (extension == ".mha" || extension == ".mhd") return ScanFormat::MetaImage;
  return std::nullopt;
}

// Which reader `path` needs. Throws BadInput for a missing path or an unknown extension.
ScanFormat scanFormatOf(const std::string& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) throw BadInput(path, "no such file or folder");
  if (fs::is_directory(status)) return ScanFormat::DicomFolder;
  const std::string extension = fileExtension(path);
  if (auto format = fileFormatOf(extension)) return *format;
  if (extension == ".dcm" || itk_seam::isDicomFile(path)) return ScanFormat::DicomFile;
  throw BadInput(path, (extension.empty() ? std::string("unknown scan format (no extension)")
                                          : "unknown scan format '" + extension + "'") +
                           "; " + kKnownFormats);
}

// Stored component types in both vocabularies; the seam cannot name PixelType (it lives beside Eigen).
constexpr std::array<std::pair<StoredType, PixelType>, 8> kTypePairs{{
    {StoredType::UInt8, PixelType::UInt8},
    {StoredType::Int8, PixelType::Int8},
    {StoredType::UInt16, PixelType::UInt16},
    {StoredType::Int16, PixelType::Int16},
    {StoredType::UInt32, PixelType::UInt32},
    {StoredType::Int32, PixelType::Int32},
    {StoredType::Float32, PixelType::Float32},
    {StoredType::Float64, PixelType::Float64},
}};

PixelType pixelTypeOf(StoredType stored) {
  return std::find_if(kTypePairs.begin(), kTypePairs.end(), [&](const auto& p) { return p.first == stored; })
      ->second;
}

StoredType storedTypeOf(PixelType pixel) {
  return std::find_if(kTypePairs.begin(), kTypePairs.end(), [&](const auto& p) { return p.second == pixel; })
      ->first;
}


itk_seam::RawHeader rawHeaderOf(const GridGeometry& geometry, PixelType pixelType) {
  itk_seam::RawHeader header;
  for (int axis = 0; axis < 3; ++axis) {
    header.size[axis] = geometry.size[axis];
    header.origin[axis] = geometry.origin[axis];
    header.spacing[axis] = geometry.spacing[axis];
    for (int column = 0; column < 3; ++column)
      header.direction[3 * axis + column] = geometry.direction(axis, column);
  }
  header.storedType = storedTypeOf(pixelType);
  return header;
}

std::string seriesListing(const std::vector<itk_seam::RawDicomSeries>& series) {
  std::string listing;
  for (const itk_seam::RawDicomSeries& s : series) {
    if (!listing.empty()) listing += ", ";
    listing += s.uid + " (" + std::to_string(s.files.size()) + (s.files.size() == 1 ? " slice)" : " slices)");
  }
  return listing;
}

itk_seam::RawVolume<float> readDicomFolder(const std::string& folder, const std::string& seriesUid) {
  const std::vector<itk_seam::RawDicomSeries> series = itk_seam::findDicomSeries(folder);
  if (series.empty()) throw BadInput(folder, "no DICOM series in this folder");
  if (seriesUid.empty()) {
    if (series.size() > 1)
      throw BadInput(folder, "holds " + std::to_string(series.size()) +
                                 " DICOM series; choose one by its series UID: " + seriesListing(series));
    return itk_seam::readDicomSlices(folder, series.front().files);
  }
  for (const itk_seam::RawDicomSeries& s : series)
    if (s.uid == seriesUid) return itk_seam::readDicomSlices(folder, s.files);
  throw UsageError(folder + ": no DICOM series with UID " + seriesUid + "; the folder holds " +
                   seriesListing(series));
}

// NaN or infinite voxels: no method here has a meaning for them (thresholds, histograms, distances and
// fits would take them as some number or spread them), and ITK casts them to 0 in integer outputs.
void checkFiniteValues(const Image& image, const std::string& path) {
  const auto bad = std::find_if(image.values.begin(), image.values.end(), [](float v) { return !std::isfinite(v); });
  if (bad == image.values.end()) return;
  const std::int64_t index = bad - image.values.begin(), nx = image.geometry.size.x(), ny = image.geometry.size.y();
  const std::int64_t count =
      std::count_if(bad, image.values.end(), [](float v) { return !std::isfinite(v); });
  std::ostringstream problem;
  problem << "voxel (" << index % nx << ", " << index / nx % ny << ", " << index / (nx * ny) << ") holds " << *bad;
  if (count > 1) problem << " (" << count << " voxels are not finite)";
  problem << "; scans must hold finite numbers";
  throw BadInput(path, problem.str());
}

Image readScanAs(const std::string& path, ScanFormat format, const ScanReadOptions& options) {
  if (format != ScanFormat::DicomFolder && !options.seriesUid.empty())
    throw UsageError(path + ": a series UID selects a series of a DICOM folder, but this is a file");
  itk_seam::RawVolume<float> raw = format == ScanFormat::DicomFolder
                                       ? readDicomFolder(path, options.seriesUid)
                                       : itk_seam::readImageFile<float>(path);
  Image image;
  image.geometry = geometryOf(raw.header);
  image.geometry.validate(path);
  image.fileType = pixelTypeOf(raw.header.storedType);
  image.values = std::move(raw.values);
  checkFiniteValues(image, path);
  return image;
}

void checkWritableFormat(const std::string& path) {
  const std::optional<ScanFormat> format = fileFormatOf(fileExtension(path));
  if (!format || fileExtension(path) == ".seg.nrrd")
    throw UsageError(path + ": cannot write images as '" + fileExtension(path) +
                     "'; use .nii, .nii.gz, .nrrd, .nhdr, .mha or .mhd");
}

void checkNotExisting(const std::string& path, const WriteOptions& options) {
  if (!options.force && fs::exists(path)) throw UsageError(path + ": exists; pass --force to replace it");
}

// .nhdr and .mhd headers name their data file after their own stem, so ITK writes them under their final
// names into a staging folder; the data file moves out first and the header last, through writeAtomically.
void writeDetachedImage(const std::string& path, const WriteOptions& options,
                        const itk_seam::RawHeader& header, const std::vector<float>& values) {
  checkNotExisting(path, options);
  const fs::path target(path);
  const TemporaryFolder staging(path);
  const fs::path stagedHeader = fs::path(staging.path()) / target.filename();
  itk_seam::writeImageFile(stagedHeader.string(), header, values);
  std::vector<fs::path> dataFiles;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging.path()))
    if (entry.path() != stagedHeader) dataFiles.push_back(entry.path());
  for (const fs::path& data : dataFiles) {
    const std::string final = (target.parent_path() / data.filename()).string();
    checkNotAnInput(final);
    checkNotExisting(final, options);
    syncFile(data.string(), final);
  }
  writeAtomically(path, options, [&](const std::string& temporaryPath) {
    for (const fs::path& data : dataFiles) fs::rename(data, target.parent_path() / data.filename());
    fs::rename(stagedHeader, temporaryPath);
  });
}

void writeImage(const std::string& path, const WriteOptions& options, const itk_seam::RawHeader& header,
                const std::vector<float>& values) {
  const std::string extension = fileExtension(path);
  try {
    if (extension == ".nhdr" || extension == ".mhd") return writeDetachedImage(path, options, header, values);
    writeAtomically(path, options, [&](const std::string& temporaryPath) {
      itk_seam::writeImageFile(temporaryPath, header, values);
    });
  } catch (const BadInput& error) {
    // ITK names the temporary or staged file; the user knows the target.
    throw BadInput(path, error.problem());
  }
}

void checkValueCount(const GridGeometry& geometry, std::size_t count, const std::string& path) {
  if (std::int64_t(count) != geometry.voxelCount())
    throw std::invalid_argument(path + ": " + std::to_string(count) + " values for a grid of " +
                                std::to_string(geometry.voxelCount()) + " voxels");
}

// The path without its extension: "seg/body.nii.gz" -> "seg/body".
std::string pathStem(const std::string& path) {
  return path.substr(0, path.size() - fileExtension(path).size());
}

// Whole numbers 0..65535 from values stored in any type; names the first voxel that is not one.
std::vector<Label> labelsFromValues(const std::vector<double>& values, const GridGeometry& geometry,
                                    const std::string& path) {
  std::vector<Label> labels(values.size());
  for (std::size_t n = 0; n < values.size(); ++n) {
    const double value = values[n];
    if (!(value >= 0 && value <= 65535 && value == std::floor(value))) {
      const std::int64_t nx = geometry.size.x(), ny = geometry.size.y(), index = std::int64_t(n);
      const std::int64_t i = index % nx, j = index / nx % ny, k = index / (nx * ny);
      std::ostringstream problem;
      problem << "voxel (" << i << ", " << j << ", " << k << ") holds " << value
              << "; labels must be whole numbers from 0 to 65535";
      throw BadInput(path, problem.str());
    }
    labels[n] = Label(value);
  }
  return labels;
}

Grid<Label> readLabelGrid(const std::string& path) {
  const itk_seam::RawHeader header = itk_seam::readImageHeader(path);
  Grid<Label> grid;
  if (header.storedType == StoredType::UInt8 || header.storedType == StoredType::UInt16) {
    itk_seam::RawVolume<std::uint16_t> raw = itk_seam::readImageFile<std::uint16_t>(path);
    grid.geometry = geometryOf(raw.header);
    grid.values = std::move(raw.values);
  } else {
    // Other types may hold fractions, negatives or large values: read exactly, then check each voxel.
    const itk_seam::RawVolume<double> raw = itk_seam::readImageFile<double>(path);
    grid.geometry = geometryOf(raw.header);
    grid.values = labelsFromValues(raw.values, grid.geometry, path);
  }
  grid.geometry.validate(path);
  return grid;
}

// The explicit table, else the first sidecar found beside the map (labelTableSidecarPaths, then
// `<stem>.csv` if it is a Slicer colour table and `<stem>.txt`), else an empty table.
LabelTable labelTableFor(const std::string& labelMapPath, const std::string& tablePath) {
  if (!tablePath.empty()) return readLabelTable(tablePath);
  std::vector<std::string> candidates = labelTableSidecarPaths(labelMapPath);
  for (const char* extension : {".csv", ".txt"}) candidates.push_back(pathStem(labelMapPath) + extension);
  for (const std::string& candidate : candidates)
    if (fs::is_regular_file(candidate) && isLabelTableFile(candidate)) return readLabelTable(candidate);
  return {};
}

// Label maps in one file that names its labels (3D Slicer segmentations, DICOM SEG, RT Structure Sets):
// no label tables beside them.
bool namesItsLabels(const std::string& path) {
  return isSlicerSegmentationPath(path) || isDicomSegPath(path) || isDicomRtStructPath(path);
}

}  // namespace

void nameUnlistedLabels(const std::vector<Label>& labels, LabelTable& table) {
  std::vector<bool> present(65536, false);
  for (Label id : labels) present[id] = true;
  for (std::size_t id = 1; id < present.size(); ++id)
    if (present[id] && !table.find(Label(id)))
      table.add(LabelEntry{Label(id), "label_" + std::to_string(id), defaultLabelColor(Label(id))});
}

void applyExplicitTable(LabelMap& map, const std::string& tablePath) {
  if (!tablePath.empty()) map.table = readLabelTable(tablePath);
  nameUnlistedLabels(map.labels.values, map.table);
}

GridGeometry geometryOf(const itk_seam::RawHeader& header) {
  GridGeometry geometry;
  for (int axis = 0; axis < 3; ++axis) {
    geometry.size[axis] = header.size[axis];
    geometry.origin[axis] = header.origin[axis];
    geometry.spacing[axis] = header.spacing[axis];
    for (int column = 0; column < 3; ++column)
      geometry.direction(axis, column) = header.direction[3 * axis + column];
  }
  return geometry;
}

Image readScan(const std::string& path, const ScanReadOptions& options) {
  return readScanAs(path, scanFormatOf(path), options);
}

void writeScan(const std::string& path, const Image& image, const WriteOptions& options) {
  checkWritableFormat(path);
  checkValueCount(image.geometry, image.values.size(), path);
  writeImage(path, options, rawHeaderOf(image.geometry, image.fileType), image.values);
}

ScanInfo describeScan(const std::string& path, const ScanReadOptions& options) {
  const ScanFormat format = scanFormatOf(path);
  ScanInfo info;
  info.format = formatName(format);
  if (format != ScanFormat::DicomFolder) {
    const itk_seam::RawHeader header = itk_seam::readImageHeader(path);
    info.components = header.components;
    if (header.components > 1) {
      info.geometry = geometryOf(header);
      info.geometry.validate(path);
      info.pixelType = pixelTypeOf(header.storedType);
      info.orientation = info.geometry.orientationCode();
      return info;
    }
  }
  const Image image = readScanAs(path, format, options);
  info.geometry = image.geometry;
  info.pixelType = image.fileType;
  info.orientation = info.geometry.orientationCode();
  const auto [low, high] = std::minmax_element(image.values.begin(), image.values.end());
  info.valueRange = ValueRange{*low, *high};
  return info;
}

LabelMap readLabelMap(const std::string& path, const std::string& tablePath) {
  const ScanFormat format = scanFormatOf(path);
  LabelMap labelMap;
  if (format == ScanFormat::DicomFile) {
    // A DICOM SEG names its segments; an explicit table still wins. Other DICOM files are refused there.
    labelMap = readDicomSeg(path).labelMap;
    applyExplicitTable(labelMap, tablePath);
    return labelMap;
  }
  if (format == ScanFormat::DicomFolder)
    throw BadInput(path, "label maps are read from NIfTI, NRRD, MetaImage or DICOM segmentation files, not a DICOM "
                         "folder");
  if (isSlicerSegmentationPath(path)) {
    // The segments name themselves; an explicit table still wins.
    labelMap = mergeSegmentationLayers(readSlicerSegmentation(path), path);
    applyExplicitTable(labelMap, tablePath);
    return labelMap;
  }
  labelMap.labels = readLabelGrid(path);
  labelMap.table = labelTableFor(path, tablePath);
  nameUnlistedLabels(labelMap.labels.values, labelMap.table);
  return labelMap;
}

void writeLabelMap(const std::string& path, const LabelMap& labelMap, const WriteOptions& options) {
  if (isSlicerSegmentationPath(path)) return writeSlicerSegmentation(path, labelMap, options);
  if (isDicomSegPath(path)) return writeDicomSeg(path, labelMap, nullptr, options);
  if (isDicomRtStructPath(path)) return writeDicomRtStruct(path, labelMap, nullptr, options);
  checkWritableFormat(path);
  const Grid<Label>& labels = labelMap.labels;
  checkValueCount(labels.geometry, labels.values.size(), path);
  const std::array<LabelTableFormat, 3> formats{
      {LabelTableFormat::Tsv, LabelTableFormat::SlicerColorTable, LabelTableFormat::ItkSnap}};
  const Label largest =
      labels.values.empty() ? 0 : *std::max_element(labels.values.begin(), labels.values.end());
  const std::vector<float> values(labels.values.begin(), labels.values.end());
  // Labels without their tables would read back with made-up names (a full disk can fail a table alone).
  writeFilesAtomically(labelMapFiles(path), options, [&](const std::vector<std::string>& files) {
    writeImage(files[0], {}, rawHeaderOf(labels.geometry, largest < 256 ? PixelType::UInt8 : PixelType::UInt16), values);
    for (std::size_t k = 0; k < formats.size(); ++k) writeLabelTable(files[k + 1], labelMap.table, {}, formats[k]);
  });
}

std::vector<std::string> labelMapFiles(const std::string& path) {
  std::vector<std::string> files{path};
  if (namesItsLabels(path)) return files;
  for (const std::string& table : labelTableSidecarPaths(path)) files.push_back(table);
  return files;
}

std::string labelTableSidecarPath(const std::string& labelMapPath) {
  return namesItsLabels(labelMapPath) ? labelMapPath : pathStem(labelMapPath) + ".tsv";
}

std::vector<std::string> labelTableSidecarPaths(const std::string& labelMapPath) {
  if (namesItsLabels(labelMapPath)) return {};
  const std::string stem = pathStem(labelMapPath);
  return {stem + ".tsv", stem + ".ctbl", stem + ".label.txt"};
}

}  // namespace vesalius::io
