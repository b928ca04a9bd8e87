// Plain CSV marker tables: label,l,p,s[,kind,status] or label,r,a,s[,...]. See marker_formats.h.
#include "vesalius/io/marker_formats.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>

namespace vesalius::io {

namespace {

struct CsvColumns {
  int label = -1, kind = -1, status = -1;
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

MarkerStatus statusValue(std::string_view v, const LineReader& reader) {
  if (v.empty()) return MarkerStatus::Defined;
  for (MarkerStatus s : {MarkerStatus::Defined, MarkerStatus::Undefined, MarkerStatus::Preview})
    if (lowerTrimmed(v) == markerStatusName(s)) return s;
  reader.fail("unknown status '" + printable(v) + "' (defined, undefined or preview)");
}

Marker readRow(std::string_view line, const CsvColumns& c, MarkerKind defaultKind, const LineReader& reader) {
  const std::vector<std::string> f = splitCsvRow(line, reader);
  if (f.size() < c.required)
    reader.fail("expected at least " + std::to_string(c.required) + " fields, found " + std::to_string(f.size()));
  Marker m;
  m.label = std::string(field(f, c.label));
  m.kind = kindValue(field(f, c.kind), defaultKind, reader);
  m.status = statusValue(field(f, c.status), reader);
  static const char* const names[3] = {"x coordinate", "y coordinate", "z coordinate"};
  bool empty = true;
  for (int i = 0; i < 3; ++i) empty = empty && field(f, c.coordinate[i]).empty();
  if (empty && m.status == MarkerStatus::Undefined) return m;
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
  std::string out = "label,l,p,s,kind,status\n";
  for (const Marker& m : set.markers) {
    out += quoteCsvField(m.label) + ",";
    if (m.status != MarkerStatus::Undefined)
      out += formatShortest(m.position.x()) + "," + formatShortest(m.position.y()) + "," +
             formatShortest(m.position.z()) + ",";
    else
      out += ",,,";
    out += std::string(markerKindName(m.kind)) + "," + markerStatusName(m.status) + "\n";
  }
  return out;
}

}  // namespace vesalius::io
