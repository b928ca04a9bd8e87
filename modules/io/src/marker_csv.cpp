// Plain CSV marker tables: label,l,p,s[,...] or label,r,a,s[,...], a superset of the table 3D Slicer's
// markups logic exports (ExportControlPointsToCSV). See marker_formats.h.
#include "vesalius/io/marker_formats.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <optional>

namespace vesalius::io {

namespace {

struct CsvColumns {
  int label = -1, kind = -1, status = -1, defined = -1, selected = -1, visible = -1, locked = -1,
      description = -1, id = -1, associatedNodeID = -1, color = -1, tags = -1;
  int coordinate[3] = {-1, -1, -1};
  double xySign = 1.0;       // -1 for r,a,s
  std::size_t required = 0;  // fields a row must have
};

std::string lowerTrimmed(std::string_view s) {
  std::string out(trim(s));
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

int columnOf(const std::vector<std::string>& names, const char* name) {
  auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : int(it - names.begin());
}

bool findTriple(const std::vector<std::string>& names, const char* const axes[3], CsvColumns& c) {
  for (int i = 0; i < 3; ++i) c.coordinate[i] = columnOf(names, axes[i]);
  return *std::min_element(std::begin(c.coordinate), std::end(c.coordinate)) >= 0;
}

CsvColumns readHeader(std::string_view line, const LineReader& reader) {
  std::vector<std::string> names;
  for (const std::string& f : splitCsvRow(line, reader)) names.push_back(lowerTrimmed(f));
  for (std::size_t i = 0; i < names.size(); ++i)
    if (!names[i].empty() && std::count(names.begin(), names.end(), names[i]) > 1)
      reader.fail("column '" + printable(names[i]) + "' appears twice");
  static const char* const lps[3] = {"l", "p", "s"};
  static const char* const ras[3] = {"r", "a", "s"};
  CsvColumns c;
  c.label = columnOf(names, "label");
  if (c.label < 0) reader.fail("the header has no 'label' column (expected label,l,p,s[,kind,status])");
  const bool hasRas = columnOf(names, "r") >= 0 || columnOf(names, "a") >= 0;
  if (hasRas && columnOf(names, "l") >= 0) reader.fail("the header mixes l,p,s and r,a,s columns");
  if (!findTriple(names, hasRas ? ras : lps, c)) reader.fail("the header needs columns l,p,s (LPS) or r,a,s (RAS)");
  c.xySign = hasRas ? -1.0 : 1.0;
  c.kind = columnOf(names, "kind");
  c.status = columnOf(names, "status");
  c.defined = columnOf(names, "defined");
  c.selected = columnOf(names, "selected");
  c.visible = columnOf(names, "visible");
  c.locked = columnOf(names, "locked");
  c.description = columnOf(names, "description");
  c.id = columnOf(names, "id");
  c.associatedNodeID = columnOf(names, "associatednodeid");
  c.color = columnOf(names, "color");
  c.tags = columnOf(names, "tags");
  c.required = std::size_t(std::max({c.label, c.coordinate[0], c.coordinate[1], c.coordinate[2]})) + 1;
  return c;
}

std::string_view field(const std::vector<std::string>& fields, int i) {
  return i >= 0 && std::size_t(i) < fields.size() ? trim(fields[std::size_t(i)]) : std::string_view();
}

MarkerKind kindValue(std::string_view v, MarkerKind fallback, const LineReader& reader) {
  if (v.empty()) return fallback;
  for (MarkerKind k : {MarkerKind::Landmark, MarkerKind::IcpMarker, MarkerKind::Attachment})
    if (lowerTrimmed(v) == markerKindName(k)) return k;
  reader.fail("unknown kind '" + printable(v) + "' (landmark, icp or attachment)");
}

// Slicer writes its bit columns as 0 and 1.
bool flagValue(std::string_view v, bool fallback, const char* what, const LineReader& reader) {
  const std::string s = lowerTrimmed(v);
  if (s.empty()) return fallback;
  if (s == "true") return true;
  if (s == "false") return false;
  return parseInteger(s, reader, what) != 0;
}

// "status" says it in full; Slicer's "defined" column says only defined or not (undefined).
MarkerStatus statusValue(std::string_view status, std::string_view defined, const LineReader& reader) {
  if (!status.empty()) {
    for (MarkerStatus s : {MarkerStatus::Defined, MarkerStatus::Undefined, MarkerStatus::Preview, MarkerStatus::Missing})
      if (lowerTrimmed(status) == markerStatusName(s)) return s;
    reader.fail("unknown status '" + printable(status) + "' (defined, undefined, preview or missing)");
  }
  return flagValue(defined, true, "defined", reader) ? MarkerStatus::Defined : MarkerStatus::Undefined;
}

std::optional<Eigen::Vector3d> colorValue(std::string_view v, const LineReader& reader) {
  const std::vector<std::string_view> parts = splitWhitespace(v);
  if (parts.empty()) return std::nullopt;
  if (parts.size() != 3) reader.fail("color must be three numbers 'r g b' in [0, 1]");
  Eigen::Vector3d c;
  for (int i = 0; i < 3; ++i) {
    c[i] = parseDouble(parts[std::size_t(i)], reader, "color");
    if (c[i] < 0.0 || c[i] > 1.0) reader.fail("color must be three numbers 'r g b' in [0, 1]");
  }
  return c;
}

std::vector<std::string> tagsValue(std::string_view v) {
  std::vector<std::string> tags;
  for (std::size_t start = 0; start <= v.size();) {
    const std::size_t comma = std::min(v.find(',', start), v.size());
    const std::string_view tag = trim(v.substr(start, comma - start));
    if (!tag.empty()) tags.emplace_back(tag);
    start = comma + 1;
  }
  return tags;
}

Marker readRow(std::string_view line, const CsvColumns& c, MarkerKind defaultKind, const LineReader& reader) {
  const std::vector<std::string> f = splitCsvRow(line, reader);
  if (f.size() < c.required)
    reader.fail("expected at least " + std::to_string(c.required) + " fields, found " + std::to_string(f.size()));
  Marker m;
  m.label = std::string(field(f, c.label));
  m.kind = kindValue(field(f, c.kind), defaultKind, reader);
  m.status = statusValue(field(f, c.status), field(f, c.defined), reader);
  m.selected = flagValue(field(f, c.selected), true, "selected", reader);
  m.visible = flagValue(field(f, c.visible), true, "visible", reader);
  m.locked = flagValue(field(f, c.locked), false, "locked", reader);
  if (c.description >= 0 && std::size_t(c.description) < f.size()) m.description = f[std::size_t(c.description)];
  m.id = std::string(field(f, c.id));
  m.associatedNodeID = std::string(field(f, c.associatedNodeID));
  m.color = colorValue(field(f, c.color), reader);
  m.tags = tagsValue(field(f, c.tags));
  static const char* const names[3] = {"x coordinate", "y coordinate", "z coordinate"};
  bool empty = true;
  for (int i = 0; i < 3; ++i) empty = empty && field(f, c.coordinate[i]).empty();
  if (empty && !hasPosition(m.status)) return m;
  for (int i = 0; i < 3; ++i) m.position[i] = parseDouble(field(f, c.coordinate[i]), reader, names[i]);
  m.position.x() *= c.xySign;
  m.position.y() *= c.xySign;
  return m;
}

}  // namespace

MarkerSet parseMarkerCsv(std::string_view text, const std::string& source, MarkerKind defaultKind) {
  LineReader reader(text, source);
  MarkerSet set;
  std::string_view line;
  bool haveHeader = false;
  CsvColumns columns;
  while (reader.next(line)) {
    if (trim(line).empty()) continue;
    if (!haveHeader) {
      columns = readHeader(line, reader);
      haveHeader = true;
    } else {
      set.markers.push_back(readRow(line, columns, defaultKind, reader));
    }
  }
  if (!haveHeader) throw BadInput(source, "empty marker table (expected a header label,l,p,s[,kind,status])");
  return set;
}

std::string formatMarkerCsv(const MarkerSet& set) {
  std::string out = "label,l,p,s,defined,selected,visible,locked,description,kind,status,id,associatedNodeID,color,tags\n";
  for (const Marker& m : set.markers) {
    out += quoteCsvField(m.label) + ",";
    if (hasPosition(m.status))
      out += formatShortest(m.position.x()) + "," + formatShortest(m.position.y()) + "," +
             formatShortest(m.position.z()) + ",";
    else
      out += ",,,";
    out += std::string(m.status == MarkerStatus::Defined ? "1," : "0,") + (m.selected ? "1," : "0,") +
           (m.visible ? "1," : "0,") + (m.locked ? "1," : "0,") + quoteCsvField(m.description) + "," +
           markerKindName(m.kind) + "," + markerStatusName(m.status) + "," + quoteCsvField(m.id) + "," +
           quoteCsvField(m.associatedNodeID) + ",";
    if (m.color)
      out += formatShortest(m.color->x()) + " " + formatShortest(m.color->y()) + " " + formatShortest(m.color->z());
    std::string tags;
    for (const std::string& tag : m.tags) {
      if (tag.find(',') != std::string::npos || trim(tag).size() != tag.size() || tag.empty())
        throw UsageError("tag '" + printable(tag) + "' of marker '" + printable(m.label) +
                         "' cannot be written: tags are comma-separated and trimmed");
      tags += (tags.empty() ? "" : ",") + tag;
    }
    out += "," + quoteCsvField(tags) + "\n";
  }
  return out;
}

}  // namespace vesalius::io
