// Legacy 3D Slicer fiducial CSV (.fcsv), read as Slicer's vtkMRMLMarkupsFiducialStorageNode reads it,
// plus the CSV and number helpers the text marker formats share. See marker_formats.h.
#include "vesalius/io/marker_formats.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <charconv>
#include <cmath>
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
  fields.push_back(std::move(field));
  return fields;
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

struct FcsvHeader {
  bool versioned = false;
  double xySign = -1.0;  // RAS, as files from before the CoordinateSystem line were
};

double coordinateSign(std::string_view value, const LineReader& reader) {
  if (value == "LPS" || value == "1") return 1.0;
  if (value == "RAS" || value == "0") return -1.0;
  if (value == "IJK" || value == "2")
    reader.fail("IJK (voxel) coordinates are not supported; save the markups as LPS or RAS");
  reader.fail("unknown CoordinateSystem '" + printable(value) + "' (LPS, RAS, 0 or 1)");
}

void checkColumns(std::string_view value, const LineReader& reader) {
  const std::vector<std::string> names = splitCsvRow(value, reader);
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
    checkColumns(value, reader);
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
    default:
      reader.fail("position status must be 0 (undefined), 1 (preview) or 2 (defined)");
  }
}

Marker readRow(std::string_view line, const FcsvHeader& header, MarkerKind kind, const LineReader& reader) {
  const std::vector<std::string> f = splitCsvRow(line, reader);
  if (f.size() < 4) reader.fail("expected id,x,y,z,... but found " + std::to_string(f.size()) + " fields");
  if (f.size() > 16)
    reader.fail(std::to_string(f.size()) + " fields, at most 16 expected (an unquoted comma in a label?)");
  Marker m;
  m.kind = kind;
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
  m.status = statusField(f, reader);
  return m;
}

int statusCode(MarkerStatus s) { return s == MarkerStatus::Undefined ? 0 : s == MarkerStatus::Preview ? 1 : 2; }

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
    if (!header.versioned)
      reader.fail("no '# Markups fiducial file version' line before the points (Slicer 3 files are not supported)");
    set.markers.push_back(readRow(line, header, defaultKind, reader));
  }
  if (!header.versioned) throw BadInput(source, "not a Slicer .fcsv file: no '# Markups fiducial file version' line");
  return set;
}

std::string formatFcsv(const MarkerSet& set) {
  std::string out =
      "# Markups fiducial file version = 4.11\n"
      "# CoordinateSystem = LPS\n"
      "# columns = id,x,y,z,ow,ox,oy,oz,vis,sel,lock,label,desc,associatedNodeID\n";
  int id = 0;
  for (const Marker& m : set.markers) {
    const Eigen::Vector3d p = m.position.allFinite() ? m.position : Eigen::Vector3d::Zero();
    out += std::to_string(++id) + "," + formatShortest(p.x()) + "," + formatShortest(p.y()) + "," +
           formatShortest(p.z()) + ",0,0,0,1," + (m.visible ? "1," : "0,") + (m.selected ? "1," : "0,") +
           (m.locked ? "1," : "0,") + quoteCsvField(m.label) + "," + quoteCsvField(m.description) + ",," +
           std::to_string(statusCode(m.status)) + ",0\n";
  }
  return out;
}

}  // namespace vesalius::io
