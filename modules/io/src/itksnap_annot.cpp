// ITK-SNAP annotation files (.annot): ITK-SNAP's Registry written as XML (Registry::WriteToXMLFile), with
// the keys of ImageAnnotationData::SaveAnnotations. See marker_formats.h for the coordinate convention.
#include "vesalius/io/marker_formats.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>

namespace vesalius::io {

namespace {

constexpr const char* kFormat = "ITK-SNAP Annotation File";

// The registry flattened: "Annotations.Element[0].Pos" -> "10.5 20.5 3.5".
using Registry = std::map<std::string, std::string>;

// Reads the XML subset Registry writes: a prolog (<?xml?>, comments, a DOCTYPE with an internal subset),
// then <registry> holding <entry key value/> and <folder key> elements.
class RegistryXmlReader {
 public:
  RegistryXmlReader(std::string_view text, const std::string& source) : text_(text), source_(source) {}
  Registry read();

 private:
  struct Open {
    std::string element, prefix;
  };
  using Attributes = std::map<std::string, std::string>;

  [[noreturn]] void fail(const std::string& problem) const {
    const auto line = 1 + std::count(text_.begin(), text_.begin() + std::ptrdiff_t(pos_), '\n');
    throw BadInput(source_, "line " + std::to_string(line) + ": " + printable(problem, 300));
  }
  bool at(std::string_view s) const { return text_.substr(pos_, s.size()) == s; }
  void skipSpace() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
  }
  void skipPast(std::string_view end) {
    const std::size_t found = text_.find(end, pos_);
    if (found == std::string_view::npos) fail("unterminated markup: no '" + std::string(end) + "'");
    pos_ = found + end.size();
  }
  void skipDoctype();
  std::string name();
  std::string decode(std::string_view raw) const;
  Attributes attributes(bool& selfClosing);
  void startElement(std::vector<Open>& stack, Registry& registry, bool& sawRoot);
  void endElement(std::vector<Open>& stack);

  std::string_view text_;
  std::size_t pos_ = 0;
  const std::string& source_;
};

void RegistryXmlReader::skipDoctype() {
  // The internal subset [...] holds '>' characters of its own declarations.
  const std::size_t bracket = text_.find('[', pos_), close = text_.find('>', pos_);
  if (bracket != std::string_view::npos && bracket < close) {
    pos_ = bracket;
    skipPast("]");
  }
  skipPast(">");
}

std::string RegistryXmlReader::name() {
  const std::size_t start = pos_;
  while (pos_ < text_.size() && (std::isalnum(static_cast<unsigned char>(text_[pos_])) ||
                                 std::string_view("_-.:").find(text_[pos_]) != std::string_view::npos))
    ++pos_;
  if (pos_ == start) fail("expected a name");
  return std::string(text_.substr(start, pos_ - start));
}

std::string RegistryXmlReader::decode(std::string_view raw) const {
  static const std::pair<std::string_view, char> named[] = {
      {"lt", '<'}, {"gt", '>'}, {"amp", '&'}, {"apos", '\''}, {"quot", '"'}};
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    const std::size_t semi = raw[i] == '&' ? raw.find(';', i) : std::string_view::npos;
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    if (semi == std::string_view::npos) fail("'&' without ';' in an attribute");
    const std::string_view entity = raw.substr(i + 1, semi - i - 1);
    auto it = std::find_if(std::begin(named), std::end(named), [&](auto& e) { return e.first == entity; });
    if (it != std::end(named)) {
      out += it->second;
    } else if (entity.size() > 1 && entity[0] == '#') {
      const bool hex = entity[1] == 'x';
      const std::string digits(entity.substr(hex ? 2 : 1));
      char* end = nullptr;
      const long code = std::strtol(digits.c_str(), &end, hex ? 16 : 10);
      if (digits.empty() || *end != '\0' || code <= 0 || code > 127)
        fail("unsupported character reference '&" + std::string(entity) + ";'");
      out += char(code);
    } else {
      fail("unknown entity '&" + std::string(entity) + ";'");
    }
    i = semi;
  }
  return out;
}

RegistryXmlReader::Attributes RegistryXmlReader::attributes(bool& selfClosing) {
  Attributes result;
  for (;;) {
    skipSpace();
    if (at("/>") || at(">")) break;
    const std::string key = name();
    skipSpace();
    if (!at("=")) fail("expected '=' after attribute " + key);
    ++pos_;
    skipSpace();
    if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) fail("expected a quoted value");
    const char quote = text_[pos_++];
    const std::size_t end = text_.find(quote, pos_);
    if (end == std::string_view::npos) fail("unterminated attribute value");
    std::string lowered = key;
    std::transform(lowered.begin(), lowered.end(), lowered.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    result[lowered] = decode(text_.substr(pos_, end - pos_));
    pos_ = end + 1;
  }
  selfClosing = at("/>");
  pos_ += selfClosing ? 2 : 1;
  return result;
}

void RegistryXmlReader::startElement(std::vector<Open>& stack, Registry& registry, bool& sawRoot) {
  ++pos_;  // '<'
  std::string element = name();
  std::transform(element.begin(), element.end(), element.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  bool selfClosing = false;
  Attributes attrs = attributes(selfClosing);
  if (element == "registry") {
    if (sawRoot || !stack.empty()) fail("<registry> must be the one root element");
    sawRoot = true;
  } else if (stack.empty() || stack.back().element == "entry") {
    fail("<" + element + "> outside a <registry> or <folder>");
  } else if (element != "folder" && element != "entry") {
    fail("unknown element <" + element + "> (a Registry holds <entry> and <folder>)");
  } else if (!attrs.count("key") || (element == "entry" && !attrs.count("value"))) {
    fail("<" + element + "> without a " + (attrs.count("key") ? "value" : "key") + " attribute");
  } else if (element == "entry") {
    registry[stack.back().prefix + attrs["key"]] = attrs["value"];
  }
  const std::string prefix = element == "folder" ? stack.back().prefix + attrs["key"] + "." : "";
  if (!selfClosing) stack.push_back({element, prefix});
}

void RegistryXmlReader::endElement(std::vector<Open>& stack) {
  pos_ += 2;  // "</"
  std::string element = name();
  std::transform(element.begin(), element.end(), element.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  skipSpace();
  if (!at(">")) fail("expected '>' after </" + element);
  ++pos_;
  if (stack.empty() || stack.back().element != element) fail("unexpected </" + element + ">");
  stack.pop_back();
}

Registry RegistryXmlReader::read() {
  Registry registry;
  std::vector<Open> stack;
  bool sawRoot = false;
  for (skipSpace(); pos_ < text_.size(); skipSpace()) {
    if (at("<?"))
      skipPast("?>");
    else if (at("<!--"))
      skipPast("-->");
    else if (at("<!DOCTYPE"))
      skipDoctype();
    else if (at("</"))
      endElement(stack);
    else if (at("<"))
      startElement(stack, registry, sawRoot);
    else
      ++pos_;  // character data, which a Registry ignores
  }
  if (!sawRoot) fail("not an ITK-SNAP Registry XML file (no <registry>)");
  if (!stack.empty()) fail("<" + stack.back().element + "> is not closed");
  return registry;
}

bool parseNumbers(const std::string& text, double* values, int count) {
  const char* p = text.c_str();
  for (int i = 0; i < count; ++i) {
    char* end = nullptr;
    values[i] = std::strtod(p, &end);
    if (end == p || !std::isfinite(values[i])) return false;
    p = end;
  }
  while (std::isspace(static_cast<unsigned char>(*p))) ++p;
  return *p == '\0';
}

Marker readLandmark(const Registry& registry, const std::string& prefix, const GridGeometry& scan, MarkerKind kind,
                    const std::string& source) {
  auto pos = registry.find(prefix + "Pos");
  double index[3];
  if (pos == registry.end() || !parseNumbers(pos->second, index, 3))
    throw BadInput(source, printable(prefix, 100) + "Pos must be three numbers");
  Marker m;
  m.kind = kind;
  auto text = registry.find(prefix + "Text");
  if (text != registry.end()) m.label = text->second;
  // Colour and tags as AbstractAnnotation::Save writes them: "r g b" in [0, 1]; "a,b,c".
  auto color = registry.find(prefix + "Color");
  double rgb[3];
  if (color != registry.end()) {
    if (!parseNumbers(color->second, rgb, 3) || *std::min_element(rgb, rgb + 3) < 0.0 || *std::max_element(rgb, rgb + 3) > 1.0)
      throw BadInput(source, printable(prefix, 100) + "Color must be three numbers in [0, 1]");
    m.color = Eigen::Vector3d(rgb[0], rgb[1], rgb[2]);
  }
  auto tags = registry.find(prefix + "Tags");
  if (tags != registry.end())
    for (std::size_t start = 0; start <= tags->second.size();) {
      const std::size_t comma = std::min(tags->second.find(',', start), tags->second.size());
      const std::string_view tag = trim(std::string_view(tags->second).substr(start, comma - start));
      if (!tag.empty()) m.tags.emplace_back(tag);
      start = comma + 1;
    }
  // ITK-SNAP image coordinates put voxel i's centre at i + 0.5.
  m.position = scan.indexToWorld(Eigen::Vector3d(index[0], index[1], index[2]) - Eigen::Vector3d::Constant(0.5));
  return m;
}

}  // namespace

MarkerSet parseItkSnapAnnotations(std::string_view text, const std::string& source, const GridGeometry& scan,
                                  MarkerKind defaultKind) {
  const Registry registry = RegistryXmlReader(text, source).read();
  auto format = registry.find("Format");
  if (format == registry.end() || format->second != kFormat)
    throw BadInput(source, "not an ITK-SNAP annotation file (no Format = \"ITK-SNAP Annotation File\")");
  double count = 0;
  auto size = registry.find("Annotations.ArraySize");
  if (size != registry.end() &&
      (!parseNumbers(size->second, &count, 1) || count < 0 || count > 1e6 || count != std::floor(count)))
    throw BadInput(source, "Annotations.ArraySize must be a count, not '" + printable(size->second) + "'");
  MarkerSet set;
  for (int i = 0; i < int(count); ++i) {
    const std::string prefix = "Annotations.Element[" + std::to_string(i) + "].";
    auto type = registry.find(prefix + "Type");
    if (type != registry.end() && type->second == "LandmarkAnnotation")
      set.markers.push_back(readLandmark(registry, prefix, scan, defaultKind, source));
  }
  return set;
}

namespace {

std::string encodeXml(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string entry(const std::string& indent, const std::string& key, const std::string& value) {
  return indent + "<entry key=\"" + encodeXml(key) + "\" value=\"" + encodeXml(value) + "\" />\n";
}

std::string threeNumbers(const Eigen::Vector3d& v) {
  return formatShortest(v.x()) + " " + formatShortest(v.y()) + " " + formatShortest(v.z());
}

// ITK-SNAP splits its tag list at commas and keeps the first word of each.
std::string tagList(const Marker& m) {
  std::string list;
  for (const std::string& tag : m.tags) {
    if (tag.empty() || tag.find_first_of(", \t\n\r") != std::string::npos)
      throw UsageError("tag '" + printable(tag) + "' of marker '" + printable(m.label) +
                       "' cannot be written to an ITK-SNAP annotation file (a tag is one word without commas)");
    list += (list.empty() ? "" : ",") + tag;
  }
  return list;
}

std::string landmarkFolder(const Marker& m, const GridGeometry& scan) {
  const Eigen::Vector3d pos = scan.worldToIndex(m.position) + Eigen::Vector3d::Constant(0.5);
  const std::string in = "      ";
  // Entries in the order Registry's std::map writes them; red is ITK-SNAP's default colour.
  return entry(in, "Color", threeNumbers(m.color.value_or(Eigen::Vector3d(1, 0, 0)))) + entry(in, "Offset", "5 5") +
         entry(in, "Plane", "2") + entry(in, "Pos", threeNumbers(pos)) + entry(in, "Selected", "0") +
         entry(in, "Tags", tagList(m)) + entry(in, "Text", m.label) + entry(in, "Type", "LandmarkAnnotation") +
         entry(in, "VisibleInAllPlanes", "1") + entry(in, "VisibleInAllSlices", "0");
}

}  // namespace

std::string formatItkSnapAnnotations(const MarkerSet& set, const GridGeometry& scan) {
  std::vector<std::pair<std::string, std::string>> folders;  // key, contents
  for (const Marker& m : set.markers) {
    if (m.status != MarkerStatus::Defined)
      throw UsageError("marker '" + printable(m.label) + "' is " + markerStatusName(m.status) +
                       "; an ITK-SNAP annotation file holds only placed landmarks");
    folders.emplace_back("Element[" + std::to_string(folders.size()) + "]", landmarkFolder(m, scan));
  }
  std::sort(folders.begin(), folders.end());  // Registry writes folders in key order: [0], [10], [1], ...
  std::string out =
      "<?xml version=\"1.0\" encoding=\"UTF-8\" ?>\n"
      "<!DOCTYPE registry [\n<!ELEMENT registry (entry*,folder*)>\n<!ELEMENT folder (entry*,folder*)>\n"
      "<!ELEMENT entry EMPTY>\n<!ATTLIST folder key CDATA #REQUIRED>\n<!ATTLIST entry key CDATA #REQUIRED>\n"
      "<!ATTLIST entry value CDATA #REQUIRED>\n]>\n<registry>\n";
  out += entry("  ", "Format", kFormat) + entry("  ", "FormatDate", "20150624");
  out += "  <folder key=\"Annotations\" >\n" + entry("    ", "ArraySize", std::to_string(folders.size()));
  for (const auto& [key, contents] : folders)
    out += "    <folder key=\"" + key + "\" >\n" + contents + "    </folder>\n";
  out += "  </folder>\n</registry>\n";
  return out;
}

}  // namespace vesalius::io
