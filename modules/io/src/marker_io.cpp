// Marker files by extension: the dispatch between readers/writers of marker_formats.h and the files.
#include "vesalius/io/marker_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
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

std::vector<std::string> markerFieldsNotKept(const std::string& path, const MarkerSet& set) {
  const Format format = formatOf(path);
  if (format == Format::Unknown || format == Format::SlicerMarkups) return {};
  auto any = [&](auto&& has) { return std::any_of(set.markers.begin(), set.markers.end(), has); };
  const bool fcsv = format == Format::Fcsv, annot = format == Format::ItkSnapAnnot;
  std::vector<std::string> lost;
  // A .fcsv read back names its set only in Slicer 3's form, which we do not write.
  if (!set.name.empty()) lost.push_back("the set's name");
  // Read back, every marker takes the reader's --kind (landmark by default).
  if ((fcsv || annot) && any([](const Marker& m) { return m.kind != MarkerKind::Landmark; })) lost.push_back("kinds");
  if (any([](const Marker& m) { return m.templatePosition.has_value(); })) lost.push_back("template positions");
  if (fcsv && any([](const Marker& m) { return m.color || !m.tags.empty(); })) lost.push_back("colours and tags");
  if (annot) {
    if (any([](const Marker& m) { return !m.id.empty(); })) lost.push_back("ids");
    if (any([](const Marker& m) { return !m.associatedNodeID.empty(); })) lost.push_back("associated nodes");
    if (any([](const Marker& m) { return !m.description.empty(); })) lost.push_back("descriptions");
    if (any([](const Marker& m) { return !m.selected || m.locked || !m.visible; }))
      lost.push_back("selected, locked and visible flags");
  }
  return lost;
}

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
