// Label tables: TotalSegmentator / Vesalius TSV and 3D Slicer colour tables (see label_table_io.h).
// Depends on core alone: the fuzz build compiles this file with clang.
#include "vesalius/io/label_table_io.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
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

// A 3D Slicer colour table line: "id name", "id name r g b" or "id name r g b a".
void parseSlicerRow(std::string_view line, LabelTable& table, const LineReader& reader) {
  const std::vector<std::string_view> tokens = splitWhitespace(line);
  if (tokens.size() != 2 && tokens.size() != 5 && tokens.size() != 6)
    reader.fail("expected 'id name r g b a' (colour table line), found " + std::to_string(tokens.size()) +
                " fields");
  std::optional<std::array<std::uint8_t, 3>> color;
  if (tokens.size() >= 5) {
    color.emplace();
    for (int c = 0; c < 3; ++c) (*color)[c] = parseColorComponent(tokens[2 + c], reader);
    if (tokens.size() == 6) parseColorComponent(tokens[5], reader);
  }
  addEntry(table, parseLabelId(tokens[0], reader), tokens[1], color, reader);
}

bool isTsvHeader(std::string_view line) { return lowerCase(splitTabs(line).front()) == "label"; }

}  // namespace

LabelTable parseLabelTable(std::string_view text, const std::string& source) {
  LineReader reader(text, source);
  LabelTable table;
  std::optional<TsvColumns> tsv;
  bool firstLine = true;
  std::string_view line;
  while (reader.next(line)) {
    if (isSkipped(line)) continue;
    if (firstLine && isTsvHeader(line)) {
      tsv = parseTsvHeader(line, reader);
    } else if (tsv) {
      parseTsvRow(line, *tsv, table, reader);
    } else {
      parseSlicerRow(line, table, reader);
    }
    firstLine = false;
  }
  return table;
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

void writeLabelTable(const std::string& path, const LabelTable& table, const WriteOptions& options) {
  std::string text;
  try {
    text = formatLabelTable(table);
  } catch (const BadInput& error) {
    throw BadInput(path, error.problem());
  }
  writeAtomically(path, options, [&](const std::string& temporaryPath) { writeFileBytes(temporaryPath, text); });
}

}  // namespace vesalius::io
