// The mesh formats read and written through VTK: PLY, VTK legacy, VTP, VTU (see mesh_io.h).
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/polydata.h"
#include "vesalius/io/text_file.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkCellTypes.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkUnstructuredGridReader.h>
#include <vtkUnstructuredGridWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLReader.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <new>
#include <numeric>
#include <sstream>
#include <type_traits>
#include <vector>

namespace vesalius::io {

namespace {

constexpr const char* kCornerUv = "corner_uv";
constexpr const char* kSpaceArray = "SPACE";  // field data tag, as 3D Slicer names it

// Keeps the first VTK error of an algorithm, so a failure becomes one BadInput line rather than text
// on stderr and an empty output. Warnings are swallowed for the same reason.
class ErrorCollector : public vtkCommand {
 public:
  static ErrorCollector* New() { return new ErrorCollector; }
  void Execute(vtkObject*, unsigned long event, void* callData) override {
    if (event != vtkCommand::ErrorEvent || !message_.empty() || !callData) return;
    std::string text(static_cast<const char*>(callData));
    // VTK prefixes "ClassName (0x...): "; the rest is the message.
    const std::size_t prefix = text.find("): ");
    if (prefix != std::string::npos) text.erase(0, prefix + 3);
    message_ = text.substr(0, text.find('\n'));
    if (message_.empty()) message_ = "VTK reported an error";
  }
  const std::string& message() const { return message_; }

 private:
  std::string message_;
};

// Catches what VTK prints with no object to observe: the legacy readers' generic warnings such as "Error
// reading ascii data. Possible mismatch of datasize with declaration." mean a broken file.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New() { return new CapturingOutputWindow; }
  void DisplayText(const char* text) override {
    if (!message_.empty() || !text) return;
    std::string message(text);
    // "Generic Warning: In <source file>, line N" comes first; the message is on the next line.
    if (message.find(": In ") < message.find('\n')) message.erase(0, message.find('\n') + 1);
    message_ = message.substr(0, message.find('\n'));
  }
  const std::string& message() const { return message_; }

 private:
  std::string message_;
};

// Installs a CapturingOutputWindow, and silences VTK's logger on stderr, for its lifetime. Both are
// global, so VTK work that uses this is serialised.
class ScopedOutputCapture {
 public:
  ScopedOutputCapture()
      : lock_(mutex()),
        previous_(vtkOutputWindow::GetInstance()),
        verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    vtkOutputWindow::SetInstance(capture_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~ScopedOutputCapture() {
    vtkLogger::SetStderrVerbosity(verbosity_);
    vtkOutputWindow::SetInstance(previous_);
  }
  const std::string& message() const { return capture_->message(); }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity verbosity_;
  vtkNew<CapturingOutputWindow> capture_;
};

// Runs `algorithm` (Update for readers, Write for writers) and throws BadInput if VTK reported an error.
template <class Algorithm, class Run>
void runChecked(Algorithm* algorithm, const std::string& path, Run run) {
  ScopedOutputCapture output;
  vtkNew<ErrorCollector> errors;
  algorithm->AddObserver(vtkCommand::ErrorEvent, errors);
  algorithm->AddObserver(vtkCommand::WarningEvent, errors);
  algorithm->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, errors);
  if constexpr (std::is_base_of_v<vtkXMLReader, Algorithm>) {
    algorithm->SetReaderErrorObserver(errors);
    algorithm->SetParserErrorObserver(errors);
  }
  const bool ok = run();
  if (!errors->message().empty()) throw BadInput(path, errors->message());
  if (!output.message().empty()) throw BadInput(path, output.message());
  if (!ok) throw BadInput(path, "VTK could not process the file");
}

void checkReadable(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path, std::string("cannot open: ") + std::strerror(errno));
}

// VTK allocates what an XML file's NumberOfPoints, NumberOfCells, ... declare before reading the data, so
// a few hundred bytes claiming 4e9 points exhaust the memory. Each declared point or cell takes at least a
// byte of data, and zlib shrinks data at most about 1032-fold, so more than that is refused.
void checkXmlDeclaredCounts(const std::string& path) {
  const std::string text = readBinaryFile(path);
  const double most = 1032.0 * double(text.size()) + 1e6;
  for (std::size_t at = text.find("NumberOf"); at != std::string::npos; at = text.find("NumberOf", at + 8)) {
    const std::size_t quote = text.find_first_of("\"'", at);
    const std::size_t equals = text.find('=', at);
    if (quote == std::string::npos || equals == std::string::npos || equals > quote) continue;
    const std::string name = text.substr(at, equals - at);
    const double count = std::strtod(text.c_str() + quote + 1, nullptr);
    const std::string value = text.substr(quote + 1, text.find_first_of("\"'", quote + 1) - quote - 1);
    if (name != "NumberOfComponents" && count > most)
      throw BadInput(path, name + "=\"" + value + "\" is more than a file of " + std::to_string(text.size()) +
                               " bytes can hold");
    // VTK takes a component count beyond int as a huge one and loops over it for minutes.
    if (name == "NumberOfComponents" && !(count >= 1 && count <= 65535))
      throw BadInput(path, "NumberOfComponents=\"" + value + "\" is not a component count (1 to 65535)");
  }
}

// Update() on a reader whose file or input string is set; throws BadInput naming `path`.
template <class Reader>
void updateChecked(Reader* reader, const std::string& path) {
  try {
    runChecked(reader, path, [reader] {
      reader->Update();
      return true;
    });
  } catch (const std::bad_alloc&) {
    throw BadInput(path, "the sizes it declares do not fit in memory");
  }
}

template <class Reader>
void readChecked(Reader* reader, const std::string& path) {
  checkReadable(path);
  if constexpr (std::is_base_of_v<vtkXMLReader, Reader>) checkXmlDeclaredCounts(path);
  reader->SetFileName(path.c_str());
  updateChecked(reader, path);
}

// Every VTK format starts with a header, so an empty file is a failed write that VTK did not report
// (vtkPLYWriter does not check its writes).
void checkNotEmpty(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size == 0) throw BadInput(path, "cannot write: nothing reached the file; is the disk full?");
}

template <class Writer>
void writeChecked(Writer* writer, const std::string& path) {
  writer->SetFileName(path.c_str());
  try {
    runChecked(writer, path,
               [writer] { return writer->Write() == 1 && writer->GetErrorCode() == vtkErrorCode::NoError; });
  } catch (const BadInput&) {
    // The error code says what went wrong more plainly than the pipeline's messages.
    const unsigned long code = writer->GetErrorCode();
    if (code == vtkErrorCode::OutOfDiskSpaceError) throw BadInput(path, "cannot write: No space left on device");
    if (code != vtkErrorCode::NoError)
      throw BadInput(path, std::string("cannot write: ") + vtkErrorCode::GetStringFromErrorCode(code));
    throw;
  }
  checkNotEmpty(path);
}

// vtkPLYReader frees memory it never allocated when a file ends early, and reads far outside its vertex
// array for a face index beyond it (a segfault), so the structure of a PLY file is walked first: the
// header's elements and properties must be matched by the data that follows, and every face's vertex
// index must name a vertex.
struct PlyProperty {
  int valueBytes = 0;
  int countBytes = 0;  // lists only: size of the count that precedes the values
  bool isFloat = false, isSigned = false;
  bool vertexIndices = false;  // the face list whose values index the vertex element
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

bool plyTypeIsFloat(const std::string& type) {
  return type == "float" || type == "float32" || type == "double" || type == "float64";
}

bool plyTypeIsSigned(const std::string& type) {
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" || type == "int32";
}

int plyTypeBytes(const std::string& type) {
  static const std::map<std::string, int> kBytes = {
      {"char", 1},   {"uchar", 1},  {"int8", 1},   {"uint8", 1},  {"short", 2},  {"ushort", 2},
      {"int16", 2},  {"uint16", 2}, {"int", 4},    {"uint", 4},   {"int32", 4},  {"uint32", 4},
      {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto found = kBytes.find(type);
  return found == kBytes.end() ? 0 : found->second;
}

// The words of a PLY header or ASCII data line as vtkPLYReader splits it: up to a NUL byte (it reads C
// strings), with the first "vertex_index" overwritten by "vertex_indices" and its terminating NUL (which
// ends the line there), at spaces, tabs and carriage returns only.
std::vector<std::string> plyWords(std::string_view text) {
  std::string line(text.substr(0, text.find('\0')));
  const std::size_t renamed = line.find("vertex_index");
  if (renamed != std::string::npos) line = line.substr(0, renamed) + "vertex_indices";
  std::vector<std::string> words;
  const auto separator = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  for (std::size_t i = 0; i < line.size();) {
    while (i < line.size() && separator(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !separator(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

// The header's format ("ascii", "binary_little_endian", "binary_big_endian") and elements; `bodyStart`
// receives the offset of the data.
std::string parsePlyHeader(const std::string& bytes, const std::string& path, std::vector<PlyElement>& elements,
                           std::size_t& bodyStart) {
  // The line whose first word is end_header, as vtkPLYReader looks for it ("end_headerX" is not it).
  std::size_t end = std::string::npos;
  for (std::size_t line = 0; line < bytes.size() && end == std::string::npos;) {
    const std::size_t next = std::min(bytes.find('\n', line), bytes.size());
    const std::vector<std::string> words = plyWords(std::string_view(bytes).substr(line, next - line));
    if (!words.empty() && words[0] == "end_header") end = line;
    line = next + 1;
  }
  const std::size_t newline = end == std::string::npos ? end : bytes.find('\n', end);
  if (bytes.rfind("ply", 0) != 0 || end == std::string::npos || newline == std::string::npos)
    throw BadInput(path, "not a PLY file (expected 'ply' ... 'end_header')");
  bodyStart = newline + 1;
  std::istringstream header(bytes.substr(0, end));
  std::string line, format;
  std::vector<std::string> vertexProperties;
  std::map<std::size_t, std::vector<std::string>> propertyNames;  // by element
  // vtkPLYReader ends the header at a line without words and indexes the words an element or property line
  // should have without counting them.
  for (int number = 1; std::getline(header, line); ++number) {
    std::vector<std::string> words = plyWords(line);
    const std::size_t needed = words.empty() ? 1
                               : words[0] == "element" ? 3
                               : words[0] == "property" ? (words.size() > 1 && words[1] == "list" ? 5 : 3)
                                                        : 1;
    if (words.size() < needed || line.size() >= 4080)
      throw BadInput(path, "PLY header line " + std::to_string(number) +
                               (words.empty()            ? " is empty"
                                : line.size() >= 4080 ? " is 4080 bytes or longer"
                                                         : " has too few words"));
    words.resize(std::max<std::size_t>(words.size(), 5));
    const std::string keyword(words[0]), a(words[1]), b(words[2]), c(words[3]);
    if (keyword == "format") format = a;
    if (keyword == "element") {
      for (const PlyElement& e : elements)
        if (e.name == a) throw BadInput(path, "PLY element '" + a + "' is declared twice");
      elements.push_back({a, std::strtoll(b.c_str(), nullptr, 10), {}});
    }
    if (keyword != "property") continue;
    if (elements.empty()) throw BadInput(path, "PLY property before any element");
    const bool list = a == "list";
    const std::string& valueType = list ? c : a;
    const std::string propertyName(words[4]);
    // vtkPLYReader reads a list of the vertices or faces it has no use for through an uninitialised
    // pointer (a segfault); the face lists it asks for are vertex_indices and texcoord.
    const std::string& element = elements.back().name;
    if (list && (element == "vertex" || element == "face") &&
        !(element == "face" &&
          (propertyName == "vertex_indices" || propertyName == "vertex_index" || propertyName == "texcoord")))
      throw BadInput(path, "PLY " + element + " property '" + propertyName +
                               "' is a list, which VTK's PLY reader cannot skip");
    // vtkPLYReader asks for a property by name and gets the first; a second of that name is one it has not
    // asked for (read through an uninitialised pointer when a list).
    const std::string name = list ? propertyName : b;
    std::vector<std::string>& names = propertyNames[elements.size() - 1];
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw BadInput(path, "PLY " + element + " property '" + name + "' is declared twice");
    names.push_back(name);
    if (elements.back().name == "vertex") vertexProperties.push_back(list ? propertyName : b);
    PlyProperty property{plyTypeBytes(valueType), list ? plyTypeBytes(b) : 0, plyTypeIsFloat(valueType),
                         plyTypeIsSigned(valueType),
                         list && elements.back().name == "face" &&
                             (propertyName == "vertex_indices" || propertyName == "vertex_index")};
    if (!property.valueBytes || (list && !property.countBytes))
      throw BadInput(path, "PLY property with an unknown type: " + line);
    elements.back().properties.push_back(property);
  }
  // vtkPLYReader frees the property list of an element without properties, which it never allocated. It
  // reads the vertices and then the faces where it finds them and skips no other element, so one before
  // them would be read as vertices or faces (indices beyond the points, a segfault).
  bool vertices = false, faces = false;
  for (const PlyElement& e : elements) {
    if (e.count < 0) throw BadInput(path, "PLY element '" + e.name + "' has a negative count");
    if (e.properties.empty()) throw BadInput(path, "PLY element '" + e.name + "' has no properties");
    if (e.name == "face" && !vertices) throw BadInput(path, "PLY faces come before the vertices");
    if (e.name != "vertex" && e.name != "face" && !(vertices && faces))
      throw BadInput(path, "PLY element '" + e.name + "' comes before the vertices or faces, which VTK's PLY reader "
                           "does not skip");
    vertices = vertices || e.name == "vertex";
    faces = faces || e.name == "face";
  }
  // vtkPLYReader segfaults on a file whose vertices lack x, y or z (in its error path), and frees memory it
  // never allocated for a file without faces or whose faces have no vertex list.
  for (const char* axis : {"x", "y", "z"})
    if (std::find(vertexProperties.begin(), vertexProperties.end(), axis) == vertexProperties.end())
      throw BadInput(path, std::string("PLY vertices have no '") + axis + "' property");
  const auto face = std::find_if(elements.begin(), elements.end(), [](const PlyElement& e) { return e.name == "face"; });
  if (face == elements.end() ||
      std::none_of(face->properties.begin(), face->properties.end(), [](const PlyProperty& p) { return p.vertexIndices; }))
    throw BadInput(path, "PLY file has no faces with a 'vertex_indices' list");
  return format;
}

[[noreturn]] void plyEndsEarly(const std::string& path, const PlyElement& e, long long i) {
  throw BadInput(path, "PLY data ends early, in " + e.name + " " + std::to_string(i + 1) + " of " +
                           std::to_string(e.count));
}

long long plyVertexCount(const std::vector<PlyElement>& elements) {
  for (const PlyElement& e : elements)
    if (e.name == "vertex") return e.count;
  return 0;
}

void checkPlyVertexIndex(double index, long long vertices, const std::string& path, long long face) {
  if (!(index >= 0 && index < double(vertices) && index == std::floor(index))) {
    std::ostringstream value;
    value << index;
    throw BadInput(path, "PLY face " + std::to_string(face + 1) + " refers to vertex " + value.str() + " of " +
                             std::to_string(vertices));
  }
}

// One binary value of `p`'s type at `at`.
double plyBinaryValue(const std::string& bytes, std::size_t at, const PlyProperty& p, bool bigEndian) {
  unsigned char raw[8];
  for (int k = 0; k < p.valueBytes; ++k)
    raw[k] = static_cast<unsigned char>(bytes[at + (bigEndian ? p.valueBytes - 1 - k : k)]);
  std::uint64_t bits = 0;
  for (int k = p.valueBytes - 1; k >= 0; --k) bits = bits << 8 | raw[k];
  if (p.isFloat) {
    if (p.valueBytes == 4) {
      float f;
      const std::uint32_t b32 = std::uint32_t(bits);
      std::memcpy(&f, &b32, 4);
      return f;
    }
    double d;
    std::memcpy(&d, &bits, 8);
    return d;
  }
  if (p.isSigned) {
    const int shift = 64 - 8 * p.valueBytes;
    return double(static_cast<std::int64_t>(bits << shift) >> shift);
  }
  return double(bits);
}

// Walks binary data, reading list counts; throws if the data ends before the header says it should.
void walkPlyBinary(const std::string& bytes, std::size_t offset, bool bigEndian,
                   const std::vector<PlyElement>& elements, const std::string& path) {
  const long long vertices = plyVertexCount(elements);
  for (const PlyElement& e : elements)
    for (long long i = 0; i < e.count; ++i)
      for (const PlyProperty& p : e.properties) {
        std::size_t values = 1;
        if (p.countBytes) {
          if (static_cast<std::size_t>(p.countBytes) > bytes.size() - offset) plyEndsEarly(path, e, i);
          values = 0;
          for (int k = 0; k < p.countBytes; ++k)
            values = values << 8 | static_cast<unsigned char>(bytes[offset + (bigEndian ? k : p.countBytes - 1 - k)]);
          offset += p.countBytes;
        }
        if (values * p.valueBytes > bytes.size() - offset) plyEndsEarly(path, e, i);
        if (p.vertexIndices)
          for (std::size_t v = 0; v < values; ++v)
            checkPlyVertexIndex(plyBinaryValue(bytes, offset + v * p.valueBytes, p, bigEndian), vertices, path, i);
        offset += values * p.valueBytes;
      }
}

// vtkPLYReader reads ASCII data a line per element, as a C string of at most 4095 bytes in which it
// lengthens "vertex_index" to "vertex_indices", and takes a missing word as a null pointer (a segfault in
// strtod); a last line without its newline reads as the end of the file, on which it frees memory twice.
// So each element must be on a line of its own, ended by a newline, holding all its values before any NUL
// byte.
void walkPlyAscii(const std::string& bytes, std::size_t offset, const std::vector<PlyElement>& elements,
                  const std::string& path) {
  const std::string_view body = std::string_view(bytes).substr(offset);
  const long long vertices = plyVertexCount(elements);
  std::size_t lineStart = 0;
  for (const PlyElement& e : elements)
    for (long long i = 0; i < e.count; ++i) {
      if (lineStart >= body.size()) plyEndsEarly(path, e, i);
      const std::size_t lineEnd = body.find('\n', lineStart);
      if (lineEnd == std::string_view::npos)
        throw BadInput(path, "PLY " + e.name + " " + std::to_string(i + 1) +
                                 " is on a line without a newline at its end");
      if (lineEnd - lineStart >= 4080)
        throw BadInput(path, "PLY " + e.name + " " + std::to_string(i + 1) + " is on a line of 4080 bytes or more");
      std::string_view line = body.substr(lineStart, lineEnd - lineStart);
      const std::vector<std::string> tokens = plyWords(line);
      lineStart = lineEnd + 1;
      std::size_t next = 0;
      for (const PlyProperty& p : e.properties) {
        if (next >= tokens.size())
          throw BadInput(path, "PLY " + e.name + " " + std::to_string(i + 1) + " has too few values on its line");
        const long long values = p.countBytes ? std::strtoll(tokens[next++].c_str(), nullptr, 10) : 1;
        if (values < 0 || static_cast<std::size_t>(values) > tokens.size() - next)
          throw BadInput(path, "PLY " + e.name + " " + std::to_string(i + 1) + " has too few values on its line");
        if (p.vertexIndices)
          for (long long v = 0; v < values; ++v)
            checkPlyVertexIndex(std::strtod(tokens[next + std::size_t(v)].c_str(), nullptr), vertices,
                                path, i);
        next += static_cast<std::size_t>(values);
      }
    }
}

void checkPlyStructure(const std::string& path) {
  const std::string bytes = readBinaryFile(path);
  std::vector<PlyElement> elements;
  std::size_t bodyStart = 0;
  const std::string format = parsePlyHeader(bytes, path, elements, bodyStart);
  if (format == "ascii")
    walkPlyAscii(bytes, bodyStart, elements, path);
  else if (format == "binary_little_endian" || format == "binary_big_endian")
    walkPlyBinary(bytes, bodyStart, format == "binary_big_endian", elements, path);
  else
    throw BadInput(path, "unknown PLY format '" + format + "'");
}

// vtkPolyDataReader closes its file when a number in a legacy cell list is malformed and then reads on from
// the closed stream (a segfault), dereferences a null FIELD when one of its arrays fails, allocates what
// POINTS, FIELD and the cell headers declare before reading anything, and builds cells from the sizes in a
// list without checking them against the list's length or the points. vtkUnstructuredGridReader reads its
// CELLS the same way, and then takes as many CELL_TYPES as there are cells, however many the file holds (a
// read beyond its array), each truncated to a byte (266 reads as a tetrahedron). So the geometry of a
// legacy POLYDATA or UNSTRUCTURED_GRID file (header, FIELD, POINTS, the cell lists VERTICES, LINES,
// POLYGONS, TRIANGLE_STRIPS or CELLS, in the layout of files before version 5 and in the
// OFFSETS/CONNECTIVITY one of 5.x, and CELL_TYPES) is walked first, word by word as vtkDataReader reads
// it, and so are its POINT_DATA and CELL_DATA attributes, whose arrays VTK also allocates from their
// declared sizes (a SCALARS line may declare billions of components) before reading a value.
struct VtkValueType {
  int bytes = 0;
  bool isFloat = false, isSigned = false;
};

// The numeric array types of the legacy format, by their (lower case) names in the file.
bool legacyVtkValueType(const std::string& name, VtkValueType& type) {
  static const std::map<std::string, VtkValueType> kTypes = {
      {"char", {1, false, true}},          {"signed_char", {1, false, true}},   {"unsigned_char", {1, false, false}},
      {"short", {2, false, true}},         {"unsigned_short", {2, false, false}}, {"vtkidtype", {4, false, true}},
      {"int", {4, false, true}},           {"unsigned_int", {4, false, false}}, {"long", {8, false, true}},
      {"unsigned_long", {8, false, false}}, {"vtktypeint64", {8, false, true}},  {"vtktypeuint64", {8, false, false}},
      {"float", {4, true, true}},          {"double", {8, true, true}}};
  const auto found = kTypes.find(name);
  if (found == kTypes.end()) return false;
  type = found->second;
  return true;
}

std::string lowerCase(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  return lower;
}

std::string upperCase(std::string_view text) {
  std::string upper(text);
  std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
  return upper;
}

bool startsWith(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

// A word of the file as a message can show it: at most 40 characters, bytes that do not print as '?'.
std::string shown(std::string_view word) {
  std::string text(word.substr(0, 40));
  for (char& c : text)
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  return word.size() > 40 ? text + "..." : text;
}

// "a hexahedron (VTK cell type 12)". VTK's table of names is indexed by the type unchecked, so a type
// outside it is not looked up.
std::string cellTypeDescription(long long type) {
  const char* className =
      type >= 0 && type < VTK_NUMBER_OF_CELL_TYPES ? vtkCellTypes::GetClassNameFromTypeId(int(type)) : nullptr;
  if (!className || std::strncmp(className, "vtk", 3) != 0)
    return "of VTK cell type " + std::to_string(type) + ", which VTK does not know";
  std::string name = className + 3;
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  return "a " + name + " (VTK cell type " + std::to_string(type) + ")";
}

class LegacyVtkWalk {
 public:
  // `unstructuredGrid`: the file must hold DATASET UNSTRUCTURED_GRID of tetrahedra, else DATASET POLYDATA.
  LegacyVtkWalk(const std::string& bytes, const std::string& path, bool unstructuredGrid)
      : bytes_(bytes), path_(path), grid_(unstructuredGrid) {}

  void run() {
    header();
    const std::string dataset = grid_ ? "UNSTRUCTURED_GRID" : "POLYDATA";
    if (!startsWith(lowerCase(word("DATASET")), "dataset"))
      fail(wordAt_, "expected DATASET " + dataset + ", found '" + shown(word_) + "'");
    if (!startsWith(lowerCase(word("the dataset type")), lowerCase(dataset).c_str()))
      fail(wordAt_, "expected DATASET " + dataset + ", found DATASET " + shown(word_));
    // The keywords in the order the readers try them (a word is taken by the first it starts with).
    while (at_ < bytes_.size()) {
      const std::string keyword = lowerCase(word(nullptr));
      if (keyword.empty()) break;
      if (startsWith(keyword, "field"))
        field();
      else if (startsWith(keyword, "points"))
        points();
      else if (!grid_ && (startsWith(keyword, "vertices") || startsWith(keyword, "lines") ||
                          startsWith(keyword, "polygons") || startsWith(keyword, "triangle_strips")))
        cells(nullptr);
      else if (grid_ && startsWith(keyword, "cells"))
        gridCells();
      else if (grid_ && startsWith(keyword, "cell_types"))
        cellTypes();
      else if (startsWith(keyword, "cell_data") || startsWith(keyword, "point_data")) {
        attributes();
        break;
      }
      else
        fail(wordAt_, "unknown keyword '" + shown(word_) + "'");
    }
    if (grid_) checkTetrahedra();
  }

  // After run(): the bytes without the METADATA blocks, or "" when there are none.
  std::string metadataRemoved() const {
    if (metadata_.empty()) return {};
    std::string kept;
    std::size_t from = 0;
    for (const auto& [begin, end] : metadata_) {
      kept.append(bytes_, from, begin - from);
      from = end;
    }
    return kept.append(bytes_, from, std::string::npos);
  }

 private:
  using OnInteger = std::function<void(long long value, std::size_t at)>;

  std::size_t lineAt(std::size_t offset) const {
    return 1 + std::count(bytes_.begin(), bytes_.begin() + std::min(offset, bytes_.size()), '\n');
  }
  [[noreturn]] void fail(std::size_t offset, const std::string& problem) const {
    throw BadInput(path_, "line " + std::to_string(lineAt(offset)) + ": " + problem);
  }
  std::size_t left() const { return bytes_.size() - at_; }

  // The next word as `operator>>` reads it; fails at the end of the file unless `what` is null.
  std::string_view word(const char* what) {
    while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    wordAt_ = at_;
    while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
    word_ = std::string_view(bytes_).substr(wordAt_, at_ - wordAt_);
    if (word_.empty() && what) fail(wordAt_, std::string("the file ends before ") + what);
    // vtkDataReader reads a word into 256 bytes and would take the rest as the next word.
    if (word_.size() >= 256) fail(wordAt_, "a word of 256 characters or more");
    return word_;
  }

  // The current word as a decimal integer in [least, most]; `what` names it in messages.
  long long parsed(const std::string& what, long long least, long long most, const std::string& in = "") const {
    const std::string text(word_);
    errno = 0;
    char* end = nullptr;
    const long long value = std::strtoll(text.c_str(), &end, 10);
    if (end != text.c_str() + text.size() || errno == ERANGE || !std::isdigit(static_cast<unsigned char>(text.back())))
      fail(wordAt_, "bad " + what + " '" + shown(text) + "'" + in);
    if (value < least || value > most)
      fail(wordAt_, what + " " + text + in + " is out of range [" + std::to_string(least) + ", " +
                        std::to_string(most) + "]");
    return value;
  }

  long long integer(const char* what, long long least, long long most) {
    word(what);
    return parsed(what, least, most);
  }

  void header() {
    const std::size_t first = std::min(bytes_.find('\n'), bytes_.size());
    const std::string line = bytes_.substr(0, std::min<std::size_t>(first, 255));
    const char* kMagic = "# vtk DataFile Version";
    if (line.rfind(kMagic, 0) != 0) fail(0, "not a legacy VTK file (expected '# vtk DataFile Version')");
    int minor = 0;
    if (std::sscanf(line.c_str() + std::strlen(kMagic), "%d.%d", &major_, &minor) != 2) major_ = 0;
    const std::size_t title = bytes_.find('\n', first + 1);
    if (first == bytes_.size() || title == std::string::npos) fail(first, "the file ends in its header");
    at_ = title + 1;
    const std::string type = lowerCase(word("ASCII or BINARY"));
    if (startsWith(type, "ascii"))
      binary_ = false;
    else if (startsWith(type, "binary"))
      binary_ = true;
    else
      fail(wordAt_, "expected ASCII or BINARY, found '" + shown(word_) + "'");
  }

  VtkValueType valueType(const char* what) {
    VtkValueType type;
    if (!legacyVtkValueType(lowerCase(word(what)), type))
      fail(wordAt_, "unsupported data type '" + shown(word_) + "' for " + what);
    return type;
  }

  // `count` values of `type`, ASCII words or big-endian binary after the end of the current line (when
  // `count` is 0, vtkDataReader's arrays skip nothing and its legacy cell lists still skip the line).
  // Integer values go to `onInteger` if given (integer data only).
  void values(const VtkValueType& type, long long count, const std::string& what, std::size_t sectionAt,
              const OnInteger* onInteger, bool skipLineWhenEmpty = false) {
    if (onInteger && type.isFloat) fail(sectionAt, what + " must be integers");
    if (binary_) {
      if (count == 0 && !skipLineWhenEmpty) return;
      // vtkDataReader skips the rest of the line with getline into 256 bytes, which fails on a longer one.
      const std::size_t newline = bytes_.find('\n', at_);
      if (newline == std::string::npos || newline - at_ >= 255)
        fail(sectionAt, "no end of line before the binary " + what);
      at_ = newline + 1;
      if (static_cast<unsigned long long>(count) > left() / type.bytes)
        fail(sectionAt, std::to_string(count) + " " + what + " take " + std::to_string(count) + " x " +
                            std::to_string(type.bytes) + " bytes, but only " + std::to_string(left()) + " follow");
      for (long long i = 0; onInteger && i < count; ++i) {
        std::uint64_t bits = 0;
        for (int k = 0; k < type.bytes; ++k)
          bits = bits << 8 | static_cast<unsigned char>(bytes_[at_ + i * type.bytes + k]);
        if (type.isSigned) {
          const int shift = 64 - 8 * type.bytes;
          (*onInteger)(static_cast<std::int64_t>(bits << shift) >> shift, sectionAt);
        } else {
          if (bits > std::uint64_t(std::numeric_limits<long long>::max()))
            fail(sectionAt, what + " hold a value beyond 2^63");
          (*onInteger)(static_cast<long long>(bits), sectionAt);
        }
      }
      at_ += std::size_t(count) * type.bytes;
      return;
    }
    // Each ASCII value takes at least one byte.
    if (static_cast<unsigned long long>(count) > left())
      fail(sectionAt, std::to_string(count) + " " + what + " are more than the " + std::to_string(left()) +
                          " bytes left can hold");
    const double bits = 8.0 * type.bytes;
    const long long most = type.bytes == 8 ? std::numeric_limits<long long>::max()
                                           : static_cast<long long>(std::pow(2.0, type.isSigned ? bits - 1 : bits) - 1);
    const long long least = type.isSigned ? (type.bytes == 8 ? std::numeric_limits<long long>::min() : -most - 1) : 0;
    for (long long i = 0; i < count; ++i) {
      if (word(nullptr).empty())
        fail(wordAt_, "the file ends after " + std::to_string(i) + " of " + std::to_string(count) + " " + what);
      if (type.isFloat) {
        const std::string text(word_);
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool decimal = text.find_first_not_of("0123456789+-.eE") == std::string::npos;
        const double largest = type.bytes == 4 ? double(std::numeric_limits<float>::max())
                                               : std::numeric_limits<double>::max();
        if (!decimal || end != text.c_str() + text.size() || !(std::abs(value) <= largest))
          fail(wordAt_, "bad value '" + shown(text) + "' in " + what);
      } else {
        const long long value = parsed("number", least, most, " in " + what);
        if (onInteger) (*onInteger)(value, wordAt_);
      }
    }
  }

  // An array as vtkDataReader::ReadArray reads it: values, then blank lines and an optional METADATA block
  // that ends at a line vtkDataReader::ReadLine takes as empty (nothing before a NUL byte but a '\r').
  // The block's extent is kept for metadataRemoved(): what VTK makes of its COMPONENT_NAMES and
  // INFORMATION lines depends on the keys it knows and may read past the empty line.
  void array(const VtkValueType& type, long long count, const std::string& what, std::size_t sectionAt,
             const OnInteger* onInteger) {
    values(type, count, what, sectionAt, onInteger);
    for (;;) {
      std::size_t p = at_;
      while (p < bytes_.size() && (bytes_[p] == ' ' || bytes_[p] == '\r')) ++p;
      // vtkDataReader looks at 256 bytes at a time and loops for ever on a window of only these two.
      if (p - at_ >= 256) fail(at_, "256 or more spaces after the " + what);
      if (p >= bytes_.size() || bytes_[p] != '\n') break;
      at_ = p + 1;
    }
    if (lowerCase(std::string_view(bytes_).substr(at_, 8)) != "metadata") return;
    const std::size_t blockAt = at_;
    for (bool first = true; at_ < bytes_.size(); first = false) {
      const std::size_t end = std::min(bytes_.find('\n', at_), bytes_.size());
      std::string_view line = std::string_view(bytes_).substr(at_, end - at_);
      at_ = std::min(end + 1, bytes_.size());
      line = line.substr(0, line.find('\0'));
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (!first && line.empty()) break;
    }
    metadata_.emplace_back(blockAt, at_);
  }

  void points() {
    const std::size_t sectionAt = wordAt_;
    if (points_ >= 0) fail(sectionAt, "a second POINTS section");
    points_ = integer("number of points", 0, static_cast<long long>(left() / 3));
    array(valueType("the points"), 3 * points_, "point coordinates", sectionAt, nullptr);
  }

  // A cell's point index must name one of the points.
  void pointIndex(long long index, std::size_t at, const std::string& section, long long cell) {
    if (index < 0 || index >= points_)
      fail(at, section + " cell " + std::to_string(cell + 1) + " refers to point " + std::to_string(index) + " of " +
                   std::to_string(points_));
  }

  // A cell list; the size of each cell goes to `sizes` if given.
  void cells(std::vector<long long>* sizes) {
    const std::size_t sectionAt = wordAt_;
    const std::string section = upperCase(word_);
    if (points_ < 0) fail(sectionAt, section + " before POINTS");
    const long long most = std::numeric_limits<long long>::max();
    if (major_ >= 5) {
      const long long offsets = integer("number of offsets", std::numeric_limits<long long>::min(), most);
      const long long connectivity = integer("connectivity size", std::numeric_limits<long long>::min(), most);
      if (offsets < 1) return;  // vtkDataReader reads no more of the section
      cellCount_ += offsets - 1;
      if (connectivity < 0) fail(sectionAt, section + " declares a negative connectivity size");
      if (lowerCase(word("OFFSETS")) != "offsets") fail(wordAt_, "expected OFFSETS, found '" + shown(word_) + "'");
      std::vector<long long> starts;  // of each cell in the connectivity, then its size
      long long index = 0, previous = 0;
      const OnInteger offset = [&](long long value, std::size_t at) {
        if ((index == 0 && value != 0) || value < previous || value > connectivity ||
            (index == offsets - 1 && value != connectivity))
          fail(at, section + " offset " + std::to_string(index + 1) + " is " + std::to_string(value) +
                       "; offsets must rise from 0 to the connectivity size " + std::to_string(connectivity));
        if (sizes && index > 0) sizes->push_back(value - previous);
        previous = value;
        starts.push_back(value);
        ++index;
      };
      array(valueType("the offsets"), offsets, section + " offsets", sectionAt, &offset);
      if (lowerCase(word("CONNECTIVITY")) != "connectivity")
        fail(wordAt_, "expected CONNECTIVITY, found '" + shown(word_) + "'");
      const std::size_t connectivityAt = wordAt_;
      long long position = 0, cell = 0;
      const OnInteger point = [&](long long value, std::size_t at) {
        while (starts[std::size_t(cell) + 1] <= position) ++cell;
        pointIndex(value, at, section, cell);
        ++position;
      };
      array(valueType("the connectivity"), connectivity, section + " connectivity", connectivityAt, &point);
      return;
    }
    const long long declared = integer("number of cells", 0, most);
    const long long size = integer("cell list size", 0, static_cast<long long>(left()));
    long long cells = 0, pointsLeft = -1;  // -1: the next value is a cell's size
    const OnInteger value = [&](long long v, std::size_t at) {
      if (pointsLeft > 0) {
        pointIndex(v, at, section, cells - 1);
        --pointsLeft;
        return;
      }
      if (v < 0) fail(at, section + " cell " + std::to_string(cells + 1) + " has a negative size");
      if (sizes) sizes->push_back(v);
      pointsLeft = v;
      ++cells;
    };
    values({4, false, true}, size, section + " values", sectionAt, &value, true);
    if (pointsLeft > 0)
      fail(sectionAt, section + " cell " + std::to_string(cells) + " runs past the " + std::to_string(size) +
                          " values declared");
    if (cells != declared)
      fail(sectionAt, section + " declares " + std::to_string(declared) + " cells, but its " + std::to_string(size) +
                          " values hold " + std::to_string(cells));
    cellCount_ += cells;
  }

  void gridCells() {
    if (cellsAt_ != std::string::npos) fail(wordAt_, "a second CELLS section");
    cellsAt_ = wordAt_;
    cells(&cellSizes_);
  }

  // As many 4-byte types as the count says; only tetrahedra are read.
  void cellTypes() {
    const std::size_t sectionAt = wordAt_;
    if (typesAt_ != std::string::npos) fail(sectionAt, "a second CELL_TYPES section");
    typesAt_ = sectionAt;
    types_ = integer("number of cell types", 0, std::numeric_limits<long long>::max());
    long long cell = 0;
    const OnInteger type = [&](long long value, std::size_t at) {
      ++cell;
      if (value != VTK_TETRA)
        fail(at, "CELL_TYPES cell " + std::to_string(cell) + " is " + cellTypeDescription(value) +
                     "; only tetrahedra are supported");
    };
    values({4, false, true}, types_, "cell types", sectionAt, &type, true);
  }

  // CELLS and CELL_TYPES both, one type per cell, four points per tetrahedron.
  void checkTetrahedra() const {
    if (cellsAt_ == std::string::npos && typesAt_ == std::string::npos) return;
    if (typesAt_ == std::string::npos) fail(cellsAt_, "CELLS without CELL_TYPES");
    if (cellsAt_ == std::string::npos) fail(typesAt_, "CELL_TYPES without CELLS");
    const long long cells = static_cast<long long>(cellSizes_.size());
    if (types_ != cells)
      fail(typesAt_, "CELL_TYPES declares " + std::to_string(types_) + " cells, CELLS " + std::to_string(cells));
    for (std::size_t c = 0; c < cellSizes_.size(); ++c)
      if (cellSizes_[c] != 4)
        fail(cellsAt_, "CELLS cell " + std::to_string(c + 1) + " has " + std::to_string(cellSizes_[c]) +
                           " points; a tetrahedron has 4");
  }

  void field() {
    word("the FIELD name");
    const long long arrays = integer("number of FIELD arrays", 0, static_cast<long long>(left()));
    for (long long i = 0; i < arrays; ++i) {
      const std::string name(word("a FIELD array"));
      if (name == "NULL_ARRAY") continue;
      const std::size_t arrayAt = wordAt_;
      const long long components = integer("number of components", 0, std::numeric_limits<int>::max());
      const long long tuples = integer("number of tuples", 0, static_cast<long long>(left()));
      const VtkValueType type = valueType("a FIELD array");
      sizedArray(type, tuples, components, "FIELD array '" + shown(name) + "'", arrayAt);
    }
  }

  // `tuples` x `components` values of a FIELD or attribute array, refused before VTK allocates them when
  // the rest of the file cannot hold that many.
  void sizedArray(const VtkValueType& type, long long tuples, long long components, const std::string& what,
                  std::size_t at) {
    if (components > 0 && tuples > static_cast<long long>(left()) / components)
      fail(at, what + " declares " + std::to_string(components) + " x " + std::to_string(tuples) +
                   " values, more than the file can hold");
    const OnInteger any = [](long long, std::size_t) {};
    array(type, components * tuples, "values of " + what, at, type.isFloat ? nullptr : &any);
  }

  // The number after a POINT_DATA or CELL_DATA keyword (the current word), which must be the number of
  // points or cells: the readers check only the first such count, and end without freeing what they read.
  long long attributeTuples() {
    const bool points = startsWith(lowerCase(word_), "point_data");
    const std::size_t at = wordAt_;
    const long long count = points ? points_ : cellCount_;
    const long long declared = integer("number of tuples", 0, std::numeric_limits<long long>::max());
    if (declared != count)
      fail(at, std::string(points ? "POINT_DATA" : "CELL_DATA") + " declares " + std::to_string(declared) +
                   (points ? " points" : " cells") + ", the file has " + std::to_string(std::max(count, 0LL)));
    return declared;
  }

  // The attributes from a POINT_DATA or CELL_DATA keyword to the end of the file, keyword by keyword in the
  // order vtkDataReader::ReadPointData and ReadCellData try them; each array holds a value or tuple per
  // point or cell.
  void attributes() {
    const long long mostComponents = std::numeric_limits<int>::max();
    long long tuples = attributeTuples();
    for (;;) {
      const std::string keyword = lowerCase(word(nullptr));
      if (keyword.empty()) return;
      const std::size_t at = wordAt_;
      const auto named = [&](const char* section) {
        return std::string(section) + " '" + shown(word((std::string("the ") + section + " name").c_str())) + "'";
      };
      if (startsWith(keyword, "scalars")) {
        const std::string what = named("SCALARS");
        const VtkValueType type = valueType("SCALARS");
        long long components = 1;
        if (lowerCase(word("LOOKUP_TABLE")) != "lookup_table") {
          components = parsed("number of SCALARS components", 1, mostComponents);
          if (lowerCase(word("LOOKUP_TABLE")) != "lookup_table")
            fail(wordAt_, what + ": expected LOOKUP_TABLE, found '" + shown(word_) + "'");
        }
        word("the lookup table name");
        sizedArray(type, tuples, components, what, at);
      } else if (startsWith(keyword, "vectors") || startsWith(keyword, "normals") ||
                 startsWith(keyword, "tensors")) {
        const long long components = startsWith(keyword, "tensors6") ? 6 : startsWith(keyword, "tensors") ? 9 : 3;
        const std::string section = upperCase(keyword.substr(0, startsWith(keyword, "tensors6") ? 8 : 7));
        const std::string what = named(section.c_str());
        sizedArray(valueType(section.c_str()), tuples, components, what, at);
      } else if (startsWith(keyword, "texture_coordinates")) {
        const std::string what = named("TEXTURE_COORDINATES");
        const long long dimension = integer("texture coordinate dimension", 1, 3);
        sizedArray(valueType("TEXTURE_COORDINATES"), tuples, dimension, what, at);
      } else if (startsWith(keyword, "global_ids") || startsWith(keyword, "pedigree_ids") ||
                 startsWith(keyword, "edge_flags")) {
        const std::string what = named("ids or flags");
        sizedArray(valueType("ids or flags"), tuples, 1, what, at);
      } else if (startsWith(keyword, "color_scalars")) {
        const std::string what = named("COLOR_SCALARS");
        const long long components = integer("number of COLOR_SCALARS components", 1, mostComponents);
        // Bytes in a binary file, values in [0, 1] in an ASCII one.
        sizedArray(binary_ ? VtkValueType{1, false, false} : VtkValueType{4, true, true}, tuples, components, what,
                   at);
      } else if (startsWith(keyword, "lookup_table")) {
        const std::string what = named("LOOKUP_TABLE");
        const long long colours = integer("number of LOOKUP_TABLE colours", 0, mostComponents);
        if (colours > static_cast<long long>(left()) / 4)
          fail(at, what + " declares " + std::to_string(colours) + " colours, more than the file can hold");
        values(binary_ ? VtkValueType{1, false, false} : VtkValueType{4, true, true}, 4 * colours,
               "colours of " + what, at, nullptr, true);
      } else if (startsWith(keyword, "field")) {
        field();
      } else if (startsWith(keyword, "cell_data") || startsWith(keyword, "point_data")) {
        tuples = attributeTuples();
      } else {
        fail(at, "unknown attribute '" + shown(word_) + "'");
      }
    }
  }

  const std::string& bytes_;
  const std::string& path_;
  std::size_t at_ = 0, wordAt_ = 0;
  std::string_view word_;
  bool binary_ = false;
  const bool grid_;
  int major_ = 0;
  long long points_ = -1;  // not declared yet
  long long cellCount_ = 0;  // in all cell lists so far
  std::vector<std::pair<std::size_t, std::size_t>> metadata_;  // [begin, end) of each METADATA block
  // Unstructured grids: where CELLS and CELL_TYPES begin (npos: not met), each cell's size, the type count.
  std::size_t cellsAt_ = std::string::npos, typesAt_ = std::string::npos;
  std::vector<long long> cellSizes_;
  long long types_ = 0;
};

// The file's bytes without its METADATA blocks if it has any (the array metadata of component names and
// information keys, which nothing here reads), else an empty string.
std::string checkLegacyVtkStructure(const std::string& path, bool unstructuredGrid) {
  const std::string bytes = readBinaryFile(path);
  LegacyVtkWalk walk(bytes, path, unstructuredGrid);
  walk.run();
  return walk.metadataRemoved();
}

bool isIntegral(int type) {
  switch (type) {
    case VTK_CHAR: case VTK_SIGNED_CHAR: case VTK_UNSIGNED_CHAR: case VTK_SHORT: case VTK_UNSIGNED_SHORT:
    case VTK_INT: case VTK_UNSIGNED_INT: case VTK_LONG: case VTK_UNSIGNED_LONG: case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG: case VTK_ID_TYPE:
      return true;
    default:
      return false;
  }
}

// Rows `rows` of array `a` as an attribute: integer when it has one integral component that fits an int.
void importArray(vtkDataArray* a, const std::string& name, const std::vector<vtkIdType>& rows, AttributeSet& out) {
  const int components = a->GetNumberOfComponents();
  const auto n = static_cast<Eigen::Index>(rows.size());
  if (isIntegral(a->GetDataType()) && components == 1) {
    Eigen::VectorXi values(n);
    bool fits = true;
    for (Eigen::Index r = 0; r < n && fits; ++r) {
      const double value = a->GetComponent(rows[r], 0);
      fits = std::abs(value) <= std::numeric_limits<int>::max();
      values(r) = fits ? static_cast<int>(value) : 0;
    }
    if (fits) {
      out.integer[name] = values;
      return;
    }
  }
  Eigen::MatrixXd values(n, components);
  for (Eigen::Index r = 0; r < n; ++r)
    for (int c = 0; c < components; ++c) values(r, c) = a->GetComponent(rows[r], c);
  out.real[name] = values;
}

// Throws unless array `a` has a value for each of `count` elements (a malformed file can say otherwise).
void checkTuples(vtkDataArray* a, vtkIdType count, const std::string& path) {
  if (a->GetNumberOfTuples() < count)
    throw BadInput(path, std::string("array '") + (a->GetName() ? a->GetName() : "") + "' has " +
                             std::to_string(a->GetNumberOfTuples()) + " values for " + std::to_string(count) +
                             " elements");
}

// Every numeric array of `data` but `skip`, restricted to `rows` (ids of `count` elements). Unnamed
// arrays are called "array<i>".
void importArrays(vtkDataSetAttributes* data, vtkIdType count, const std::vector<vtkIdType>& rows,
                  AttributeSet& out, const std::string& path, vtkDataArray* skip = nullptr,
                  const char* skipName = nullptr) {
  for (int i = 0; i < data->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = data->GetArray(i);
    if (!a || a == skip) continue;
    const std::string name = a->GetName() && *a->GetName() ? a->GetName() : "array" + std::to_string(i);
    if (skipName && name == skipName) continue;
    checkTuples(a, count, path);
    importArray(a, name, rows, out);
  }
}

void exportArrays(const AttributeSet& attributes, vtkDataSetAttributes* data) {
  for (const auto& [name, values] : attributes.integer) {
    vtkNew<vtkIntArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfValues(values.size());
    for (Eigen::Index r = 0; r < values.size(); ++r) a->SetValue(r, values(r));
    data->AddArray(a);
  }
  for (const auto& [name, values] : attributes.real) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name.c_str());
    a->SetNumberOfComponents(static_cast<int>(values.cols()));
    a->SetNumberOfTuples(values.rows());
    for (Eigen::Index r = 0; r < values.rows(); ++r)
      for (Eigen::Index c = 0; c < values.cols(); ++c) a->SetComponent(r, static_cast<int>(c), values(r, c));
    data->AddArray(a);
  }
}

std::vector<vtkIdType> allRows(vtkIdType count) {
  std::vector<vtkIdType> rows(static_cast<std::size_t>(count));
  std::iota(rows.begin(), rows.end(), vtkIdType(0));
  return rows;
}

MatrixX3d importPoints(vtkPointSet* data) {
  MatrixX3d V(data->GetNumberOfPoints(), 3);
  double p[3];
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    data->GetPoint(i, p);
    V.row(i) << p[0], p[1], p[2];
  }
  return V;
}

vtkSmartPointer<vtkPoints> exportPoints(const MatrixX3d& V) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) points->SetPoint(i, V(i, 0), V(i, 1), V(i, 2));
  return points;
}

// UV/FUV from per-corner uv values (#F by 6), sharing exactly equal values.
void importCornerUv(const Eigen::MatrixXd& corners, TriMesh& mesh) {
  std::map<std::pair<double, double>, int> index;
  std::vector<Eigen::Vector2d> uv;
  mesh.FUV.resize(corners.rows(), 3);
  for (Eigen::Index f = 0; f < corners.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const std::pair<double, double> key(corners(f, 2 * c), corners(f, 2 * c + 1));
      const auto [it, inserted] = index.try_emplace(key, static_cast<int>(uv.size()));
      if (inserted) uv.emplace_back(key.first, key.second);
      mesh.FUV(f, c) = it->second;
    }
  mesh.UV.resize(static_cast<Eigen::Index>(uv.size()), 2);
  for (std::size_t i = 0; i < uv.size(); ++i) mesh.UV.row(static_cast<Eigen::Index>(i)) = uv[i];
}

// Fan-triangulates the polygons; `sourceCells` receives the cell id (into cell data) of each triangle.
MatrixX3i importPolygons(vtkPolyData* data, std::vector<vtkIdType>& sourceCells, const std::string& path) {
  const vtkIdType firstPolygonCell = data->GetNumberOfVerts() + data->GetNumberOfLines();
  std::vector<int> faces;
  auto it = vtk::TakeSmartPointer(data->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
    vtkIdType size;
    const vtkIdType* ids;
    it->GetCurrentCell(size, ids);
    if (size < 3) throw BadInput(path, "polygon " + std::to_string(it->GetCurrentCellId()) + " has " +
                                           std::to_string(size) + " vertices");
    for (vtkIdType k = 1; k + 1 < size; ++k) {
      for (vtkIdType corner : {ids[0], ids[k], ids[k + 1]}) faces.push_back(static_cast<int>(corner));
      sourceCells.push_back(firstPolygonCell + it->GetCurrentCellId());
    }
  }
  return detail::fromRows(faces, 3);
}

TriMesh importPolyData(vtkPolyData* data, const std::string& path) {
  if (data->GetNumberOfStrips() > 0) throw BadInput(path, "triangle strips are not supported");
  TriMesh mesh;
  mesh.V = importPoints(data);
  std::vector<vtkIdType> sourceCells;
  mesh.F = importPolygons(data, sourceCells, path);
  const vtkIdType points = data->GetNumberOfPoints(), cells = data->GetNumberOfCells();
  vtkDataArray* tcoords = data->GetPointData()->GetTCoords();
  importArrays(data->GetPointData(), points, allRows(points), mesh.vertexAttributes, path, tcoords);
  importArrays(data->GetCellData(), cells, sourceCells, mesh.faceAttributes, path, nullptr, kCornerUv);
  vtkDataArray* cornerUv = data->GetCellData()->GetArray(kCornerUv);
  if (cornerUv && cornerUv->GetNumberOfComponents() == 6) {
    checkTuples(cornerUv, cells, path);
    AttributeSet corners;
    importArray(cornerUv, kCornerUv, sourceCells, corners);
    importCornerUv(corners.real.at(kCornerUv), mesh);
  } else if (tcoords && tcoords->GetNumberOfComponents() >= 2) {
    checkTuples(tcoords, points, path);
    mesh.UV.resize(mesh.V.rows(), 2);
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
      mesh.UV.row(i) << tcoords->GetComponent(i, 0), tcoords->GetComponent(i, 1);
    mesh.FUV = mesh.F;
  }
  return mesh;
}

// The uv of each vertex (#V by 2) if every corner at a vertex has the same uv; false at a seam.
bool perVertexUv(const TriMesh& mesh, MatrixX2d& uv) {
  uv = MatrixX2d::Zero(mesh.V.rows(), 2);
  std::vector<bool> set(static_cast<std::size_t>(mesh.V.rows()), false);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int v = mesh.F(f, c);
      const Eigen::RowVector2d value = mesh.UV.row(mesh.FUV(f, c));
      if (set[v] && uv.row(v) != value) return false;
      uv.row(v) = value;
      set[v] = true;
    }
  return true;
}

void exportUv(const TriMesh& mesh, vtkPolyData* data) {
  if (mesh.FUV.rows() == 0) return;
  MatrixX2d uv;
  if (perVertexUv(mesh, uv)) {
    vtkNew<vtkDoubleArray> tcoords;
    tcoords->SetName("TCoords");
    tcoords->SetNumberOfComponents(2);
    tcoords->SetNumberOfTuples(uv.rows());
    for (Eigen::Index i = 0; i < uv.rows(); ++i) tcoords->SetTuple2(i, uv(i, 0), uv(i, 1));
    data->GetPointData()->SetTCoords(tcoords);
    return;
  }
  AttributeSet corners;
  Eigen::MatrixXd& values = corners.real[kCornerUv];
  values.resize(mesh.F.rows(), 6);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) values.block<1, 2>(f, 2 * c) = mesh.UV.row(mesh.FUV(f, c));
  exportArrays(corners, data->GetCellData());
}

vtkSmartPointer<vtkPolyData> exportPolyData(const TriMesh& mesh) {
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(exportPoints(mesh.V));
  vtkNew<vtkCellArray> polys;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const vtkIdType ids[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    polys->InsertNextCell(3, ids);
  }
  data->SetPolys(polys);
  exportArrays(mesh.vertexAttributes, data->GetPointData());
  exportArrays(mesh.faceAttributes, data->GetCellData());
  exportUv(mesh, data);
  return data;
}

TetMesh importUnstructuredGrid(vtkUnstructuredGrid* data, const std::string& path) {
  TetMesh mesh;
  mesh.V = importPoints(data);
  mesh.T.resize(data->GetNumberOfCells(), 4);
  for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c) {
    const int type = data->GetCellType(c);
    if (type != VTK_TETRA)
      throw BadInput(path, "cell " + std::to_string(c) + " is " + cellTypeDescription(type) +
                               "; only tetrahedra are supported");
    vtkIdType size;
    const vtkIdType* ids;
    data->GetCellPoints(c, size, ids);
    if (size != 4)
      throw BadInput(path, "tetrahedron " + std::to_string(c) + " has " + std::to_string(size) + " points");
    for (int k = 0; k < 4; ++k) mesh.T(c, k) = static_cast<int>(ids[k]);
  }
  const vtkIdType points = data->GetNumberOfPoints(), cells = data->GetNumberOfCells();
  importArrays(data->GetPointData(), points, allRows(points), mesh.vertexAttributes, path);
  importArrays(data->GetCellData(), cells, allRows(cells), mesh.tetAttributes, path);
  return mesh;
}

vtkSmartPointer<vtkUnstructuredGrid> exportUnstructuredGrid(const TetMesh& mesh) {
  auto data = vtkSmartPointer<vtkUnstructuredGrid>::New();
  data->SetPoints(exportPoints(mesh.V));
  vtkNew<vtkCellArray> cells;
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    const vtkIdType ids[4] = {mesh.T(t, 0), mesh.T(t, 1), mesh.T(t, 2), mesh.T(t, 3)};
    cells->InsertNextCell(4, ids);
  }
  data->SetCells(VTK_TETRA, cells);
  exportArrays(mesh.vertexAttributes, data->GetPointData());
  exportArrays(mesh.tetAttributes, data->GetCellData());
  return data;
}

SpaceTag fieldDataTag(vtkDataObject* data) {
  auto* tag = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(kSpaceArray));
  if (!tag || tag->GetNumberOfValues() < 1) return SpaceTag::kNone;
  return findSpaceTag(std::string(kSpaceArray) + "=" + tag->GetValue(0));
}

void addFieldDataTag(vtkDataObject* data) {
  vtkNew<vtkStringArray> tag;
  tag->SetName(kSpaceArray);
  tag->InsertNextValue("LPS");
  data->GetFieldData()->AddArray(tag);
}

SpaceTag commentTag(vtkStringArray* comments) {
  for (vtkIdType i = 0; comments && i < comments->GetNumberOfValues(); ++i)
    if (findSpaceTag(comments->GetValue(i)) == SpaceTag::kRas) return SpaceTag::kRas;
  return SpaceTag::kNone;
}

template <class Reader>
void readLegacy(Reader* reader, const std::string& path, bool unstructuredGrid) {
  checkReadable(path);
  const std::string withoutMetadata = checkLegacyVtkStructure(path, unstructuredGrid);
  reader->ReadAllScalarsOn();
  reader->ReadAllVectorsOn();
  reader->ReadAllNormalsOn();
  reader->ReadAllTensorsOn();
  reader->ReadAllColorScalarsOn();
  reader->ReadAllTCoordsOn();
  reader->ReadAllFieldsOn();
  if (withoutMetadata.empty()) {
    reader->SetFileName(path.c_str());
  } else {
    if (withoutMetadata.size() > std::size_t(std::numeric_limits<int>::max()))
      throw BadInput(path, "a legacy VTK file of 2 GB or more with METADATA blocks is not supported");
    reader->ReadFromInputStringOn();
    reader->SetBinaryInputString(withoutMetadata.data(), int(withoutMetadata.size()));
  }
  updateChecked(reader, path);
}

template <class Writer>
void configureLegacyWriter(Writer* writer, bool binary) {
  writer->SetFileVersion(vtkDataWriter::VTK_LEGACY_READER_VERSION_4_2);
  writer->SetHeader("Vesalius, millimetres, SPACE=LPS");
  writer->SetFileType(binary ? VTK_BINARY : VTK_ASCII);
}

}  // namespace

TriMesh readVtkSurface(const std::string& path) {
  const std::string ext = fileExtension(path);
  TriMesh mesh;
  SpaceTag tag = SpaceTag::kNone;
  if (ext == ".ply") {
    checkPlyStructure(path);
    vtkNew<vtkPLYReader> reader;
    reader->SetDuplicatePointsForFaceTexture(false);  // keep the surface connected
    readChecked(reader.Get(), path);
    mesh = importPolyData(reader->GetOutput(), path);
    tag = commentTag(reader->GetComments());
  } else if (ext == ".vtk") {
    vtkNew<vtkPolyDataReader> reader;
    readLegacy(reader.Get(), path, false);
    mesh = importPolyData(reader->GetOutput(), path);
    tag = findSpaceTag(reader->GetHeader() ? reader->GetHeader() : "");
  } else if (ext == ".vtp") {
    vtkNew<vtkXMLPolyDataReader> reader;
    readChecked(reader.Get(), path);
    mesh = importPolyData(reader->GetOutput(), path);
    tag = fieldDataTag(reader->GetOutput());
  } else {
    throw BadInput(path, "not a VTK surface format (.ply, .vtk, .vtp)");
  }
  if (tag == SpaceTag::kRas) flipRasLps(mesh.V);
  mesh.validate(path);
  return mesh;
}

TetMesh readVtkTetMesh(const std::string& path) {
  const std::string ext = fileExtension(path);
  TetMesh mesh;
  SpaceTag tag = SpaceTag::kNone;
  if (ext == ".vtu") {
    vtkNew<vtkXMLUnstructuredGridReader> reader;
    readChecked(reader.Get(), path);
    mesh = importUnstructuredGrid(reader->GetOutput(), path);
    tag = fieldDataTag(reader->GetOutput());
  } else if (ext == ".vtk") {
    vtkNew<vtkUnstructuredGridReader> reader;
    readLegacy(reader.Get(), path, true);
    mesh = importUnstructuredGrid(reader->GetOutput(), path);
    tag = findSpaceTag(reader->GetHeader() ? reader->GetHeader() : "");
  } else {
    throw BadInput(path, "not a VTK tet mesh format (.vtu, .vtk)");
  }
  if (tag == SpaceTag::kRas) flipRasLps(mesh.V);
  mesh.validate(path);
  orientTetsPositively(mesh.V, mesh.T);
  return mesh;
}

void writeVtkSurface(const TriMesh& mesh, const std::string& path, bool binary) {
  const std::string ext = fileExtension(path);
  const vtkSmartPointer<vtkPolyData> data = exportPolyData(mesh);
  if (ext == ".ply") {
    // vtkPLYWriter takes the texture coordinates to be floats (and crashes otherwise).
    if (vtkDataArray* tcoords = data->GetPointData()->GetTCoords()) {
      vtkNew<vtkFloatArray> floats;
      floats->DeepCopy(tcoords);
      data->GetPointData()->SetTCoords(floats);
    }
    vtkNew<vtkPLYWriter> writer;
    writer->SetInputData(data);
    writer->SetFileType(binary ? VTK_BINARY : VTK_ASCII);
    writer->AddComment("SPACE=LPS");
    writeChecked(writer.Get(), path);
    // A PLY file cut short by a full disk is found by the reader's own walk of its structure.
    try {
      checkPlyStructure(path);
    } catch (const BadInput& error) {
      throw BadInput(path, "cannot write: the file written is incomplete (" + error.problem() + "); is the disk full?");
    }
  } else if (ext == ".vtk") {
    vtkNew<vtkPolyDataWriter> writer;
    writer->SetInputData(data);
    configureLegacyWriter(writer.Get(), binary);
    writeChecked(writer.Get(), path);
  } else if (ext == ".vtp") {
    addFieldDataTag(data);
    vtkNew<vtkXMLPolyDataWriter> writer;
    writer->SetInputData(data);
    if (!binary) writer->SetDataModeToAscii();
    writeChecked(writer.Get(), path);
  } else {
    throw UsageError(path + ": not a VTK surface format (.ply, .vtk, .vtp)");
  }
}

void writeVtkTetMesh(const TetMesh& mesh, const std::string& path, bool binary) {
  const std::string ext = fileExtension(path);
  const vtkSmartPointer<vtkUnstructuredGrid> data = exportUnstructuredGrid(mesh);
  if (ext == ".vtu") {
    addFieldDataTag(data);
    vtkNew<vtkXMLUnstructuredGridWriter> writer;
    writer->SetInputData(data);
    if (!binary) writer->SetDataModeToAscii();
    writeChecked(writer.Get(), path);
  } else if (ext == ".vtk") {
    vtkNew<vtkUnstructuredGridWriter> writer;
    writer->SetInputData(data);
    configureLegacyWriter(writer.Get(), binary);
    writeChecked(writer.Get(), path);
  } else {
    throw UsageError(path + ": not a VTK tet mesh format (.vtu, .vtk)");
  }
}

TriMesh fromPolyData(vtkPolyData* data, const std::string& source) { return importPolyData(data, source); }

vtkSmartPointer<vtkPolyData> toPolyData(const TriMesh& mesh) { return exportPolyData(mesh); }

}  // namespace vesalius::io
