// Legacy 3D Slicer fiducial CSV (.fcsv), read as Slicer's vtkMRMLMarkupsFiducialStorageNode reads it,
// plus the CSV and number helpers the text marker formats share. See marker_formats.h.
#include "vesalius/io/marker_formats.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <charconv>
#include <cmath>
#include <set>
#include <string>

namespace vesalius::io {

std::string formatShortest(double value) {
  char buffer[32];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string printable(std::string_view text, std::size_t maxLength) {
  std::string out;
  for (char c : text.substr(0, maxLength)) out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
  return text.size() > maxLength ? out + "..." : out;
}

std::vector<std::string> splitCsvRow(std::string_view line, const LineReader& reader, char separator) {
  if (line.find('\r') != std::string_view::npos) reader.fail("carriage return inside a line");
  enum class State { Unquoted, Quoted, QuoteInQuoted } state = State::Unquoted;
  std::vector<std::string> fields;
  std::string field;
  for (char c : line) {
    if (state == State::Unquoted) {
      if (c == separator) {
        fields.push_back(std::move(field));
        field.clear();
      } else if (c == '"' && field.empty()) {
        state = State::Quoted;  // only a quote that opens a field starts quoting, as in Slicer
      } else {
        field += c;
      }
    } else if (state == State::Quoted) {
      if (c == '"')
        state = State::QuoteInQuoted;
      else
        field += c;
    } else if (c == '"') {  // "" inside quotes
      field += '"';
      state = State::Quoted;
    } else {
      // After the closing quote: a separator ends the field; anything else is kept, as Slicer keeps it.
      if (c == separator) {
        fields.push_back(std::move(field));
        field.clear();
      } else {
        field += c;
      }
      state = State::Unquoted;
    }
  }
  // A quote left open would take the rest of the row, separators and all, into one field.
  if (state == State::Quoted)
    reader.fail("field " + std::to_string(fields.size() + 1) + " opens a quote that is never closed");
  fields.push_back(std::move(field));
  return fields;
}

std::vector<std::string> uniqueMarkerIds(const std::vector<const Marker*>& markers) {
  std::set<std::string> taken;
  std::vector<std::string> ids;
  for (const Marker* m : markers) ids.push_back(!m->id.empty() && taken.insert(m->id).second ? m->id : "");
  int next = 1;
  for (std::string& id : ids) {
    if (!id.empty()) continue;
    while (taken.count(std::to_string(next))) ++next;
    id = std::to_string(next);
    taken.insert(id);
  }
  return ids;
}

std::string quoteCsvField(const std::string& field, char separator) {
  if (field.find_first_of("\r\n") != std::string::npos)
    throw UsageError("cannot write '" + printable(field) + "' to a CSV-like file: it holds a line break");
  if (field.find(separator) == std::string::npos && field.find('"') == std::string::npos) return field;
  std::string quoted = "\"";
  for (char c : field) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

namespace {

constexpr const char* kColumns[] = {"id", "x",   "y",   "z",    "ow",    "ox",   "oy",
                                    "oz", "vis", "sel", "lock", "label", "desc", "associatedNodeID"};
constexpr std::size_t kColumnCount = sizeof kColumns / sizeof kColumns[0];

// Slicer 3's fiducial list, which Slicer reads when a file has no version line: one point per row as
// label,x,y,z,sel,vis, RAS, no quoting.
constexpr const char* kSlicer3Columns[] = {"label", "x", "y", "z", "sel", "vis"};
constexpr std::size_t kSlicer3ColumnCount = sizeof kSlicer3Columns / sizeof kSlicer3Columns[0];

struct FcsvHeader {
  bool versioned = false;
  double xySign = -1.0;  // RAS, as files from before the CoordinateSystem line were
  std::string name;      // Slicer 3's "# name = ..."
};

double coordinateSign(std::string_view value, const LineReader& reader) {
  if (value == "LPS" || value == "1") return 1.0;
  if (value == "RAS" || value == "0") return -1.0;
  if (value == "IJK" || value == "2")
    reader.fail("IJK (voxel) coordinates are not supported; save the markups as LPS or RAS");
  reader.fail("unknown CoordinateSystem '" + printable(value) + "' (LPS, RAS, 0 or 1)");
}

void checkColumns(std::string_view value, const FcsvHeader& header, const LineReader& reader) {
  const std::vector<std::string> names = splitCsvRow(value, reader);
  if (!header.versioned) {  // Slicer 3
    bool slicer3 = names.size() >= 4 && names.size() <= kSlicer3ColumnCount;
    for (std::size_t i = 0; slicer3 && i < names.size(); ++i) slicer3 = trim(names[i]) == kSlicer3Columns[i];
    if (!slicer3)
      reader.fail("unsupported columns '" + printable(value) +
                  "' (a file without '# Markups fiducial file version' is Slicer 3's: label,x,y,z,sel,vis)");
    return;
  }
  bool standard = names.size() >= kColumnCount;
  for (std::size_t i = 0; standard && i < kColumnCount; ++i) standard = trim(names[i]) == kColumns[i];
  if (!standard)
    reader.fail("unsupported columns '" + printable(value) +
                "' (expected id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID)");
}

void readHeaderLine(std::string_view line, FcsvHeader& header, const LineReader& reader) {
  line.remove_prefix(1);  // '#'
  const std::size_t eq = line.find('=');
  if (eq == std::string_view::npos) return;  // a plain comment
  const std::string_view name = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
  if (name == "Markups fiducial file version")
    header.versioned = true;
  else if (name == "CoordinateSystem")
    header.xySign = coordinateSign(value, reader);
  else if (name == "columns")
    checkColumns(value, header, reader);
  else if (name == "name" && !header.versioned)
    header.name = std::string(value);
}

bool present(const std::vector<std::string>& fields, std::size_t i) {
  return i < fields.size() && !trim(fields[i]).empty();
}

bool flagField(const std::vector<std::string>& fields, std::size_t i, bool fallback, const LineReader& reader) {
  if (!present(fields, i)) return fallback;
  return parseInteger(trim(fields[i]), reader, kColumns[i]) != 0;
}

MarkerStatus statusField(const std::vector<std::string>& fields, const LineReader& reader) {
  if (!present(fields, 14)) return MarkerStatus::Defined;
  switch (parseInteger(trim(fields[14]), reader, "position status")) {
    case 0:
      return MarkerStatus::Undefined;
    case 1:
      return MarkerStatus::Preview;
    case 2:
      return MarkerStatus::Defined;
    case 3:
      return MarkerStatus::Missing;
    default:
      reader.fail("position status must be 0 (undefined), 1 (preview), 2 (defined) or 3 (missing)");
  }
}

Marker readRow(std::string_view line, const FcsvHeader& header, MarkerKind kind, const LineReader& reader) {
  const std::vector<std::string> f = splitCsvRow(line, reader);
  if (f.size() < 4) reader.fail("expected id,x,y,z,... but found " + std::to_string(f.size()) + " fields");
  if (f.size() > 16)
    reader.fail(std::to_string(f.size()) + " fields, at most 16 expected (an unquoted comma in a label?)");
  Marker m;
  m.kind = kind;
  m.id = std::string(trim(f[0]));
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p[i] = parseDouble(trim(f[1 + i]), reader, kColumns[1 + i]);
  m.position = Eigen::Vector3d(header.xySign * p.x(), header.xySign * p.y(), p.z());
  // The orientation quaternion has no place in a Marker, but a broken one means a broken row.
  for (std::size_t i = 4; i < 8; ++i)
    if (present(f, i)) parseDouble(trim(f[i]), reader, kColumns[i]);
  m.visible = flagField(f, 8, true, reader);
  m.selected = flagField(f, 9, true, reader);
  m.locked = flagField(f, 10, false, reader);
  if (f.size() > 11) m.label = f[11];
  if (f.size() > 12) m.description = f[12];
  if (f.size() > 13) m.associatedNodeID = std::string(trim(f[13]));
  m.status = statusField(f, reader);
  return m;
}

// Split on every comma, as Slicer splits a Slicer 3 row (its labels are not quoted).
Marker readSlicer3Row(std::string_view line, MarkerKind kind, const LineReader& reader) {
  if (line.find('\r') != std::string_view::npos) reader.fail("carriage return inside a line");
  std::vector<std::string_view> f;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    f.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (f.size() < 4 || f.size() > kSlicer3ColumnCount)
    reader.fail("a Slicer 3 row (no version line) is label,x,y,z[,sel,vis], found " + std::to_string(f.size()) +
                " fields");
  Marker m;
  m.kind = kind;
  m.label = std::string(f[0]);
  for (int i = 0; i < 3; ++i) m.position[i] = parseDouble(trim(f[1 + std::size_t(i)]), reader, kSlicer3Columns[1 + i]);
  m.position.x() = -m.position.x();  // RAS
  m.position.y() = -m.position.y();
  if (f.size() > 4 && !trim(f[4]).empty()) m.selected = parseInteger(trim(f[4]), reader, "sel") != 0;
  if (f.size() > 5 && !trim(f[5]).empty()) m.visible = parseInteger(trim(f[5]), reader, "vis") != 0;
  return m;
}

int statusCode(MarkerStatus s) {
  switch (s) {
    case MarkerStatus::Undefined: return 0;
    case MarkerStatus::Preview: return 1;
    case MarkerStatus::Defined: return 2;
    case MarkerStatus::Missing: return 3;
  }
  return 2;
}

}  // namespace

MarkerSet parseFcsv(std::string_view text, const std::string& source, MarkerKind defaultKind) {
  LineReader reader(text, source);
  FcsvHeader header;
  MarkerSet set;
  std::string_view line;
  while (reader.next(line)) {
    if (trim(line).empty()) continue;
    if (line.front() == '#') {
      readHeaderLine(line, header, reader);
      continue;
    }
    set.markers.push_back(header.versioned ? readRow(line, header, defaultKind, reader)
                                           : readSlicer3Row(line, defaultKind, reader));
  }
  set.name = header.name;
  return set;
}

std::string formatFcsv(const MarkerSet& set) {
  std::string out =
      "# Markups fiducial file version = 4.11\n"
      "# CoordinateSystem = LPS\n"
      "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n";
  std::vector<const Marker*> markers;
  for (const Marker& m : set.markers) markers.push_back(&m);
  const std::vector<std::string> ids = uniqueMarkerIds(markers);
  for (std::size_t i = 0; i < set.markers.size(); ++i) {
    const Marker& m = set.markers[i];
    // Slicer writes the stored coordinates of a point without a position; ours are zero.
    const Eigen::Vector3d p = hasPosition(m.status) && m.position.allFinite() ? m.position : Eigen::Vector3d::Zero();
    // An id that begins with '#' is quoted, or its row would be read back as a header line.
    const std::string id = quoteCsvField(ids[i]);
    out += (id.rfind('#', 0) == 0 ? "\"" + id + "\"" : id) + "," + formatShortest(p.x()) + "," + formatShortest(p.y()) + "," +
           formatShortest(p.z()) + ",0,0,0,1," + (m.visible ? "1," : "0,") + (m.selected ? "1," : "0,") +
           (m.locked ? "1," : "0,") + quoteCsvField(m.label) + "," + quoteCsvField(m.description) + "," +
           quoteCsvField(m.associatedNodeID) + "," + std::to_string(statusCode(m.status)) + ",0\n";
  }
  return out;
}

}  // namespace vesalius::io
