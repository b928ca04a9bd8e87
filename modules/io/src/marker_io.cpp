// Marker files by extension: the dispatch between readers/writers of marker_formats.h and the files.
#include "vesalius/io/marker_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"
#include "vesalius/io/text_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace vesalius::io {

namespace {

enum class Format { SlicerMarkups, Fcsv, Csv, ItkSnapAnnot, Unknown };

Format formatOf(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".mrk.json") return Format::SlicerMarkups;
  if (ext == ".fcsv") return Format::Fcsv;
  if (ext == ".csv") return Format::Csv;
  if (ext == ".annot") return Format::ItkSnapAnnot;
  return Format::Unknown;
}

constexpr const char* kKnown = ".mrk.json, .fcsv, .csv or .annot";

std::string formatText(const std::string& path, const MarkerSet& set, const GridGeometry* scanGeometry) {
  switch (formatOf(path)) {
    case Format::SlicerMarkups:
      return formatSlicerMarkups(set);
    case Format::Fcsv:
      return formatFcsv(set);
    case Format::Csv:
      return formatMarkerCsv(set);
    case Format::ItkSnapAnnot:
      if (!scanGeometry) throw UsageError(path + ": writing ITK-SNAP annotations needs the scan's geometry");
      return formatItkSnapAnnotations(set, *scanGeometry);
    case Format::Unknown:
      break;
  }
  throw UsageError(path + ": unknown marker file extension (expected " + kKnown + ")");
}

}  // namespace

bool isMarkerFile(const std::string& path) { return formatOf(path) != Format::Unknown; }

MarkerSet readMarkers(const std::string& path, const MarkerReadOptions& options) {
  const Format format = formatOf(path);
  if (format == Format::Unknown)
    throw BadInput(path, std::string("unknown marker file extension (expected ") + kKnown + ")");
  if (format == Format::ItkSnapAnnot && !options.scanGeometry)
    throw BadInput(path, "ITK-SNAP annotations are in voxel coordinates: give the scan they were placed on");
  const std::string text = readTextFile(path);
  MarkerSet set;
  switch (format) {
    case Format::SlicerMarkups:
      set = parseSlicerMarkups(text, path, options.defaultKind);
      break;
    case Format::Fcsv:
      set = parseFcsv(text, path, options.defaultKind);
      break;
    case Format::Csv:
      set = parseMarkerCsv(text, path, options.defaultKind);
      break;
    default:
      set = parseItkSnapAnnotations(text, path, *options.scanGeometry, options.defaultKind);
      break;
  }
  set.validate(path);
  return set;
}

void writeMarkers(const std::string& path, const MarkerSet& set, const WriteOptions& options,
                  const GridGeometry* scanGeometry) {
  const std::string text = formatText(path, set, scanGeometry);
  writeAtomically(path, options, [&](const std::string& temporaryPath) { writeFileBytes(temporaryPath, text); });
}

}  // namespace vesalius::io
