// Label tables: TotalSegmentator / Vesalius TSV, 3D Slicer colour tables (.ctbl/.txt and .csv) and ITK-SNAP
// label description files (see label_table_io.h).
// Depends on core alone: the fuzz build compiles this file with clang.
#include "vesalius/io/label_table_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

namespace vesalius::io {

namespace {

bool isSkipped(std::string_view line) {
  const std::string_view text = trim(line);
  return text.empty() || text.front() == '#';
}

std::string lowerCase(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return lower;
}

std::vector<std::string_view> splitTabs(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t tab = line.find('\t', start);
    fields.push_back(trim(line.substr(start, tab == std::string_view::npos ? tab : tab - start)));
    if (tab == std::string_view::npos) return fields;
    start = tab + 1;
  }
}

Label parseLabelId(std::string_view token, const LineReader& reader) {
  const long long id = parseInteger(token, reader, "label id");
  if (id < 0 || id > 65535) reader.fail("label id " + std::to_string(id) + " is outside 0..65535");
  return Label(id);
}

std::uint8_t parseColorComponent(std::string_view token, const LineReader& reader) {
  const long long value = parseInteger(token, reader, "colour component");
  if (value < 0 || value > 255)
    reader.fail("colour component " + std::to_string(value) + " is outside 0..255");
  return std::uint8_t(value);
}

// Adds a parsed row; id 0 is the background, which tables do not list.
void addEntry(LabelTable& table, Label id, std::string_view name,
              const std::optional<std::array<std::uint8_t, 3>>& color, const LineReader& reader) {
  if (id == 0) return;
  if (name.empty()) reader.fail("empty name for label " + std::to_string(id));
  if (table.find(id)) reader.fail("label " + std::to_string(id) + " is listed twice");
  table.add(LabelEntry{id, std::string(name), color ? *color : defaultLabelColor(id)});
}

// Column positions of a TSV header; r, g, b are optional but come together.
struct TsvColumns {
  std::size_t label = 0, name = 0;
  std::optional<std::array<std::size_t, 3>> rgb;
  std::size_t needed = 0;  // fields a row must have
};

TsvColumns parseTsvHeader(std::string_view line, const LineReader& reader) {
  const std::vector<std::string_view> fields = splitTabs(line);
  auto column = [&](const char* title) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < fields.size(); ++i)
      if (lowerCase(fields[i]) == title) return i;
    return std::nullopt;
  };
  const auto name = column("name"), r = column("r"), g = column("g"), b = column("b");
  if (!name) reader.fail("header has no 'name' column");
  if ((r || g || b) && !(r && g && b))
    reader.fail("header names some but not all of the colour columns r, g, b");
  TsvColumns columns;
  columns.name = *name;
  columns.needed = std::max(columns.label, columns.name) + 1;
  if (r) {
    columns.rgb = std::array<std::size_t, 3>{{*r, *g, *b}};
    columns.needed = std::max({columns.needed, *r + 1, *g + 1, *b + 1});
  }
  return columns;
}

void parseTsvRow(std::string_view line, const TsvColumns& columns, LabelTable& table,
                 const LineReader& reader) {
  const std::vector<std::string_view> fields = splitTabs(line);
  if (fields.size() < columns.needed)
    reader.fail("expected " + std::to_string(columns.needed) + " tab-separated columns, found " +
                std::to_string(fields.size()));
  std::optional<std::array<std::uint8_t, 3>> color;
  if (columns.rgb) {
    color.emplace();
    for (int c = 0; c < 3; ++c) (*color)[c] = parseColorComponent(fields[(*columns.rgb)[c]], reader);
  }
  addEntry(table, parseLabelId(fields[columns.label], reader), fields[columns.name], color, reader);
}

// A colour component written as a number: Slicer writes rgba * 255 through a stream, which may print a
// fraction; rounded to the nearest whole value.
std::uint8_t parseColorNumber(std::string_view token, const LineReader& reader) {
  const double value = parseDouble(token, reader, "colour component");
  if (!(value >= 0 && value <= 255)) reader.fail("colour component " + std::string(token) + " is outside 0..255");
  return std::uint8_t(std::lround(value));
}

// A 3D Slicer colour table line: "id name", "id name r g b" or "id name r g b a".
void parseSlicerRow(std::string_view line, LabelTable& table, const LineReader& reader) {
  const std::vector<std::string_view> tokens = splitWhitespace(line);
  if (tokens.size() != 2 && tokens.size() != 5 && tokens.size() != 6)
    reader.fail("expected 'id name r g b a' (colour table line), found " + std::to_string(tokens.size()) +
                " fields");
  std::optional<std::array<std::uint8_t, 3>> color;
  if (tokens.size() >= 5) {
    color.emplace();
    for (int c = 0; c < 3; ++c) (*color)[c] = parseColorNumber(tokens[2 + c], reader);
    if (tokens.size() == 6) parseColorNumber(tokens[5], reader);
  }
  addEntry(table, parseLabelId(tokens[0], reader), tokens[1], color, reader);
}

// An ITK-SNAP label description line: IDX -R- -G- -B- -A-- VIS MSH "LABEL", alpha 0..1, the label quoted
// (ITK-SNAP reads it up to the next quote, so it holds none).
void parseItkSnapRow(std::string_view line, LabelTable& table, const LineReader& reader) {
  const std::size_t open = line.find('"');
  const std::vector<std::string_view> tokens = splitWhitespace(line.substr(0, open));
  if (tokens.size() != 7)
    reader.fail("expected 'IDX R G B A VIS MSH \"LABEL\"' (ITK-SNAP label description line), found " +
                std::to_string(tokens.size()) + " fields before the label");
  const std::size_t close = open == std::string_view::npos ? open : line.find('"', open + 1);
  if (close == std::string_view::npos) reader.fail("the label is not closed by a quote");
  if (!trim(line.substr(close + 1)).empty()) reader.fail("text after the quoted label");
  std::array<std::uint8_t, 3> color{};
  for (int c = 0; c < 3; ++c) color[c] = parseColorComponent(tokens[1 + c], reader);
  const double alpha = parseDouble(tokens[4], reader, "alpha");
  if (!(alpha >= 0 && alpha <= 1)) reader.fail("alpha " + std::string(tokens[4]) + " is outside 0..1");
  for (int flag = 5; flag < 7; ++flag) {
    const long long value = parseInteger(tokens[flag], reader, flag == 5 ? "visibility" : "mesh visibility");
    if (value != 0 && value != 1) reader.fail(std::string(tokens[flag]) + " is not a 0 or 1 visibility flag");
  }
  const Label id = parseLabelId(tokens[0], reader);
  std::string_view name = line.substr(open + 1, close - open - 1);
  // ITK-SNAP lets a label's description be empty; the id still needs a name here.
  const std::string fallback = "label_" + std::to_string(id);
  if (trim(name).empty()) name = fallback;
  addEntry(table, id, name, color, reader);
}

// Fields of one comma-separated line (RFC 4180 quoting: "a, b" and "" for a quote).
std::vector<std::string> splitCsv(std::string_view line, const LineReader& reader) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        fields.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        fields.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c != '\r') {
      fields.back() += c;
    }
  }
  if (quoted) reader.fail("a quoted field is not closed");
  for (std::string& field : fields) field = std::string(trim(field));
  return fields;
}

// Column positions of a Slicer colour table CSV header (LabelValue,Name,Color_R,Color_G,Color_B[,Color_A],
// terminology columns...); the colour columns are optional but come together.
struct CsvColumns {
  std::size_t label = 0, name = 0;
  std::optional<std::array<std::size_t, 3>> rgb;
  std::optional<std::size_t> alpha;
  std::size_t needed = 0;
};

CsvColumns parseCsvHeader(std::string_view line, const LineReader& reader) {
  const std::vector<std::string> fields = splitCsv(line, reader);
  auto column = [&](const char* title) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < fields.size(); ++i)
      if (lowerCase(fields[i]) == title) return i;
    return std::nullopt;
  };
  const auto label = column("labelvalue"), name = column("name"), r = column("color_r"), g = column("color_g"),
             b = column("color_b");
  if (!label || !name) reader.fail("colour table header needs the columns LabelValue and Name");
  if ((r || g || b) && !(r && g && b))
    reader.fail("header names some but not all of the colour columns Color_R, Color_G, Color_B");
  CsvColumns columns;
  columns.label = *label;
  columns.name = *name;
  columns.needed = std::max(*label, *name) + 1;
  if (r) {
    columns.rgb = std::array<std::size_t, 3>{{*r, *g, *b}};
    columns.needed = std::max({columns.needed, *r + 1, *g + 1, *b + 1});
  }
  columns.alpha = column("color_a");
  if (columns.alpha) columns.needed = std::max(columns.needed, *columns.alpha + 1);
  return columns;
}

void parseCsvRow(std::string_view line, const CsvColumns& columns, LabelTable& table, const LineReader& reader) {
  const std::vector<std::string> fields = splitCsv(line, reader);
  if (fields.size() < columns.needed)
    reader.fail("expected " + std::to_string(columns.needed) + " comma-separated columns, found " +
                std::to_string(fields.size()));
  std::optional<std::array<std::uint8_t, 3>> color;
  if (columns.rgb) {
    color.emplace();
    for (int c = 0; c < 3; ++c) (*color)[c] = parseColorNumber(fields[(*columns.rgb)[c]], reader);
  }
  if (columns.alpha) parseColorNumber(fields[*columns.alpha], reader);
  addEntry(table, parseLabelId(fields[columns.label], reader), fields[columns.name], color, reader);
}

// ITK-SNAP's seven numbers, then the quoted label; a Slicer line may hold a quote inside its name.
bool isItkSnapRow(std::string_view line) {
  const std::size_t quote = line.find('"');
  return quote != std::string_view::npos && splitWhitespace(line.substr(0, quote)).size() == 7;
}

bool isTsvHeader(std::string_view line) { return lowerCase(splitTabs(line).front()) == "label"; }

bool isCsvHeader(std::string_view line) {
  const std::size_t comma = line.find(',');
  return comma != std::string_view::npos && lowerCase(trim(line.substr(0, comma))) == "labelvalue";
}

std::string_view withoutByteOrderMark(std::string_view text) {
  return text.substr(0, 3) == "\xEF\xBB\xBF" ? text.substr(3) : text;
}

// Names in a Slicer colour table line cannot hold whitespace: Slicer stores a space as '_' (and restores
// it on reading, which we do not: our names keep the underscore they were written with).
std::string slicerName(const LabelEntry& entry) {
  std::string name = entry.name;
  for (char& c : name)
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  return name;
}

}  // namespace

LabelTable parseLabelTable(std::string_view text, const std::string& source) {
  LineReader reader(withoutByteOrderMark(text), source);
  LabelTable table;
  enum class Kind { Unknown, Tsv, Csv, Slicer, ItkSnap } kind = Kind::Unknown;
  std::optional<TsvColumns> tsv;
  std::optional<CsvColumns> csv;
  std::string_view line;
  while (reader.next(line)) {
    if (isSkipped(line)) continue;
    if (kind == Kind::Unknown) {
      // The first line that is not a comment decides the format.
      if (isTsvHeader(line)) {
        kind = Kind::Tsv;
        tsv = parseTsvHeader(line, reader);
        continue;
      }
      if (isCsvHeader(line)) {
        kind = Kind::Csv;
        csv = parseCsvHeader(line, reader);
        continue;
      }
      kind = isItkSnapRow(line) ? Kind::ItkSnap : Kind::Slicer;
    }
    switch (kind) {
      case Kind::Tsv: parseTsvRow(line, *tsv, table, reader); break;
      case Kind::Csv: parseCsvRow(line, *csv, table, reader); break;
      case Kind::ItkSnap: parseItkSnapRow(line, table, reader); break;
      default: parseSlicerRow(line, table, reader); break;
    }
  }
  return table;
}

bool isLabelTableFile(const std::string& path) {
  const std::string extension = fileExtension(path);
  if (extension == ".tsv" || extension == ".ctbl" || extension == ".txt" || extension == ".label") return true;
  if (extension != ".csv") return false;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    std::string_view text = line;
    if (first && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    first = false;
    if (isSkipped(text)) continue;
    return isCsvHeader(text);
  }
  return false;
}

LabelTable readLabelTable(const std::string& path) { return parseLabelTable(readTextFile(path), path); }

std::string formatLabelTable(const LabelTable& table) {
  std::string text = "label\tname\tr\tg\tb\n";
  for (const LabelEntry& entry : table.entries) {
    if (entry.name.find_first_of("\t\r\n") != std::string::npos)
      throw BadInput("", "name of label " + std::to_string(entry.id) +
                             " holds a tab or line break, which a TSV label table cannot carry");
    text += std::to_string(entry.id) + '\t' + entry.name;
    for (std::uint8_t component : entry.color) text += '\t' + std::to_string(component);
    text += '\n';
  }
  return text;
}

std::string formatSlicerColorTable(const LabelTable& table) {
  std::string text = "# Color table file written by Vesalius\n# " + std::to_string(table.entries.size() + 1) +
                     " values\n0 background 0 0 0 0\n";
  for (const LabelEntry& entry : table.entries) {
    text += std::to_string(entry.id) + ' ' + slicerName(entry);
    for (std::uint8_t component : entry.color) text += ' ' + std::to_string(component);
    text += " 255\n";  // opaque: Slicer shows a label with alpha 0 as invisible
  }
  return text;
}

std::string formatItkSnapLabels(const LabelTable& table) {
  // ITK-SNAP recognises the file by its second line (ColorLabelTable::ValidateFile).
  std::string text =
      "################################################\n"
      "# ITK-SnAP Label Description File\n"
      "# File format: \n"
      "# IDX   -R-  -G-  -B-  -A--  VIS MSH  LABEL\n"
      "# Fields: \n"
      "#    IDX:   Zero-based index \n"
      "#    -R-:   Red color component (0..255)\n"
      "#    -G-:   Green color component (0..255)\n"
      "#    -B-:   Blue color component (0..255)\n"
      "#    -A-:   Label transparency (0.00 .. 1.00)\n"
      "#    VIS:   Label visibility (0 or 1)\n"
      "#    MSH:   Label mesh visibility (0 or 1)\n"
      "#  LABEL:   Label description \n"
      "################################################\n";
  auto row = [&](Label id, const std::array<std::uint8_t, 3>& color, const char* alphaAndFlags,
                 const std::string& name) {
    char numbers[64];
    std::snprintf(numbers, sizeof numbers, "  %5u  %3u  %3u  %3u  %s    \"", unsigned(id), unsigned(color[0]),
                  unsigned(color[1]), unsigned(color[2]), alphaAndFlags);
    text += numbers + name + "\"\n";
  };
  row(0, {{0, 0, 0}}, "   0  0  0", "Clear Label");
  for (const LabelEntry& entry : table.entries) {
    // ITK-SNAP reads a label up to the next quote, and a line up to its end.
    std::string name = entry.name;
    for (char& c : name) {
      if (c == '"') c = '\'';
      if (c == '\r' || c == '\n') c = ' ';
    }
    row(entry.id, entry.color, "   1  1  1", name);
  }
  return text;
}

void writeLabelTable(const std::string& path, const LabelTable& table, const WriteOptions& options,
                     LabelTableFormat format) {
  std::string text;
  try {
    switch (format) {
      case LabelTableFormat::Tsv: text = formatLabelTable(table); break;
      case LabelTableFormat::SlicerColorTable: text = formatSlicerColorTable(table); break;
      case LabelTableFormat::ItkSnap: text = formatItkSnapLabels(table); break;
    }
  } catch (const BadInput& error) {
    throw BadInput(path, error.problem());
  }
  writeAtomically(path, options, [&](const std::string& temporaryPath) { writeFileBytes(temporaryPath, text); });
}

}  // namespace vesalius::io
