// MEDIT .mesh, ASCII (mesh_formats.h), as written by TetGen, MMG and CGAL: free-format keywords,
// counts and numbers, "#" comments, vertex numbers from 1.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <limits>
#include <map>
#include <vector>

namespace vesalius::io {

namespace {

// The file as a stream of whitespace-separated tokens, comments removed, keeping line numbers.
class TokenReader {
 public:
  TokenReader(std::string_view text, const std::string& source) : reader_(text, source) {}

  bool next(std::string_view& token) {
    while (index_ >= tokens_.size()) {
      std::string_view line;
      if (!reader_.next(line)) return false;
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) ras_ = ras_ || findSpaceTag(line.substr(hash)) == SpaceTag::kRas;
      tokens_ = splitWhitespace(line.substr(0, hash));
      index_ = 0;
    }
    token = tokens_[index_++];
    return true;
  }

  std::string_view require(const std::string& what) {
    std::string_view token;
    if (!next(token)) reader_.fail("file ends while reading " + what);
    return token;
  }
  long long integer(const std::string& what) { return parseInteger(require(what), reader_, what.c_str()); }
  double real(const std::string& what) { return parseDouble(require(what), reader_, what.c_str()); }
  // A count or a vertex number: at least `minimum` and small enough for an int.
  int bounded(const std::string& what, long long minimum) {
    const long long value = integer(what);
    if (value < minimum || value > std::numeric_limits<int>::max())
      reader_.fail("bad " + what + " " + std::to_string(value));
    return static_cast<int>(value);
  }
  [[noreturn]] void fail(const std::string& problem) const { reader_.fail(problem); }
  bool ras() const { return ras_; }

 private:
  LineReader reader_;
  std::vector<std::string_view> tokens_;
  std::size_t index_ = 0;
  bool ras_ = false;
};

// Sections read into the mesh: vertex count per element (0 for Vertices, which are coordinates).
const std::map<std::string, int> kElementSections = {{"vertices", 0}, {"triangles", 3}, {"tetrahedra", 4}};
// Sections skipped: numbers per record. They hold nothing a TetMesh keeps.
const std::map<std::string, int> kSkippedSections = {
    {"edges", 3},           {"corners", 1},           {"ridges", 1},          {"requiredvertices", 1},
    {"requirededges", 1},   {"requiredtriangles", 1}, {"requiredtetrahedra", 1}, {"normals", 3},
    {"tangents", 3},        {"normalatvertices", 2},  {"tangentatvertices", 2}};

struct Section {
  std::vector<double> xyz;   // Vertices: flattened #V by 3
  std::vector<int> indices;  // elements: flattened #elements by k, 1-based as in the file
  std::vector<int> refs;
  bool seen = false;
};

void readSection(TokenReader& in, const std::string& name, int k, Section& section) {
  if (section.seen) in.fail("second '" + name + "' section");
  section.seen = true;
  const int count = in.bounded(name + " count", 0);
  for (int i = 0; i < count; ++i) {
    for (int c = 0; c < (k ? k : 3); ++c) {
      if (k)
        section.indices.push_back(in.bounded("vertex number", 1));
      else
        section.xyz.push_back(in.real("vertex coordinate"));
    }
    section.refs.push_back(static_cast<int>(in.integer("reference")));
  }
}

void skipSection(TokenReader& in, const std::string& name, int numbersPerRecord) {
  const int count = in.bounded(name + " count", 0);
  for (long long i = 0; i < static_cast<long long>(count) * numbersPerRecord; ++i) in.require(name);
}

// #elements by k 0-based indices from the 1-based numbers of a section.
template <int K>
Eigen::Matrix<int, Eigen::Dynamic, K> elements(const Section& section, Eigen::Index vertexCount, const char* what,
                                               const std::string& source) {
  const Eigen::Index rows = static_cast<Eigen::Index>(section.indices.size() / K);
  Eigen::Matrix<int, Eigen::Dynamic, K> out(rows, K);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (int c = 0; c < K; ++c) {
      const int number = section.indices[r * K + c];
      if (number > vertexCount)
        throw BadInput(source, std::string(what) + " " + std::to_string(r + 1) + " refers to vertex " +
                                   std::to_string(number) + ", but there are " + std::to_string(vertexCount) +
                                   " vertices");
      out(r, c) = number - 1;
    }
  return out;
}

std::string lowerCase(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

void readHeaderNumber(TokenReader& in, const std::string& keyword) {
  const long long value = in.integer(keyword);
  if (keyword == "dimension" && value != 3) in.fail("dimension " + std::to_string(value) + " (only 3 is supported)");
  if (keyword == "meshversionformatted" && (value < 1 || value > 4))
    in.fail("unknown MeshVersionFormatted " + std::to_string(value));
}

void appendElements(std::string& out, const char* keyword, const Eigen::MatrixXi& elements,
                    const Eigen::VectorXi& refs) {
  out += keyword;
  out += '\n';
  detail::appendInteger(out, elements.rows());
  out += '\n';
  for (Eigen::Index r = 0; r < elements.rows(); ++r) {
    for (Eigen::Index c = 0; c < elements.cols(); ++c) {
      detail::appendInteger(out, elements(r, c) + 1LL);
      out += ' ';
    }
    detail::appendInteger(out, refs(r));
    out += '\n';
  }
}

}  // namespace

TetMesh parseMedit(std::string_view text, const std::string& source) {
  TokenReader in(text, source);
  std::map<std::string, Section> sections;
  std::string_view token;
  while (in.next(token)) {
    const std::string keyword = lowerCase(token);
    if (keyword == "end") break;
    if (keyword == "meshversionformatted" || keyword == "dimension")
      readHeaderNumber(in, keyword);
    else if (kElementSections.count(keyword))
      readSection(in, std::string(token), kElementSections.at(keyword), sections[keyword]);
    else if (kSkippedSections.count(keyword))
      skipSection(in, std::string(token), kSkippedSections.at(keyword));
    else
      in.fail("section '" + std::string(token) + "' is not supported (only Vertices, Triangles, Tetrahedra)");
  }
  if (!sections["vertices"].seen) throw BadInput(source, "no 'Vertices' section");
  const Section& vertices = sections["vertices"];
  TetMesh mesh;
  mesh.V = detail::fromRows(vertices.xyz, 3);
  mesh.T = elements<4>(sections["tetrahedra"], mesh.V.rows(), "tetrahedron", source);
  mesh.F = elements<3>(sections["triangles"], mesh.V.rows(), "triangle", source);
  detail::addReferenceColumn(mesh.vertexAttributes, kLabel, vertices.refs);
  detail::addReferenceColumn(mesh.tetAttributes, kLabel, sections["tetrahedra"].refs);
  detail::addReferenceColumn(mesh.faceAttributes, kLabel, sections["triangles"].refs);
  if (in.ras()) flipRasLps(mesh.V);
  orientTetsPositively(mesh.V, mesh.T);
  mesh.validate(source);
  return mesh;
}

std::string formatMedit(const TetMesh& mesh) {
  std::string out = "# MEDIT mesh written by Vesalius, millimetres, SPACE=LPS\nMeshVersionFormatted 2\nDimension 3\n";
  const Eigen::VectorXi vertexRefs = detail::referenceColumn(mesh.vertexAttributes, kLabel, mesh.V.rows());
  out += "Vertices\n";
  detail::appendInteger(out, mesh.V.rows());
  out += '\n';
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      detail::appendReal(out, mesh.V(i, k));
      out += ' ';
    }
    detail::appendInteger(out, vertexRefs(i));
    out += '\n';
  }
  if (mesh.F.rows() > 0)
    appendElements(out, "Triangles", mesh.F, detail::referenceColumn(mesh.faceAttributes, kLabel, mesh.F.rows()));
  if (mesh.T.rows() > 0)
    appendElements(out, "Tetrahedra", mesh.T, detail::referenceColumn(mesh.tetAttributes, kLabel, mesh.T.rows()));
  out += "End\n";
  return out;
}

}  // namespace vesalius::io
