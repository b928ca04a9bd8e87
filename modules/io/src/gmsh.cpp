// Gmsh .msh, version 1 ($NOD/$ELM) and version 2 ASCII ($MeshFormat/$Nodes/$Elements), as described
// in the Gmsh reference manual ("Legacy formats" and "MSH file format version 2").
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <unordered_map>
#include <vector>

namespace vesalius::io {

namespace {

constexpr int kPoint = 15, kLine = 1, kLine3 = 8, kTriangle = 2, kTetrahedron = 4;

// Element types we read or skip, with their node counts.
const std::map<long long, int> kNodesPerType = {
    {kPoint, 1}, {kLine, 2}, {kLine3, 3}, {kTriangle, 3}, {kTetrahedron, 4}};
const std::map<long long, const char*> kTypeNames = {
    {3, "quadrangle"},          {5, "hexahedron"},         {6, "prism"},
    {7, "pyramid"},             {9, "6-node triangle"},    {10, "9-node quadrangle"},
    {11, "10-node tetrahedron"}, {12, "27-node hexahedron"}, {16, "8-node quadrangle"},
    {17, "20-node hexahedron"}};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// Triangles or tets with their physical and elementary tags.
struct Elements {
  std::vector<int> vertices;  // flattened #elements by k
  std::vector<int> physical, elementary;
};

class GmshParser {
 public:
  GmshParser(std::string_view text, const std::string& source) : reader_(text, source) {}

  TetMesh parse() {
    std::string_view line;
    while (nextLine(line)) {
      if (line[0] != '$') reader_.fail("expected a section such as $Nodes, found '" + std::string(line) + "'");
      const std::string_view name = line.substr(1);
      if (equalsIgnoringCase(name, "MeshFormat"))
        readFormat();
      else if (name == "NOD" || name == "Nodes")
        readNodes();
      else if (name == "ELM" || name == "Elements")
        readElements(name == "ELM");
      else {
        skipSection(name);
        continue;
      }
      expectEnd(name);
    }
    return build();
  }

 private:
  // Next non-blank line, trimmed; false at the end.
  bool nextLine(std::string_view& line) {
    while (reader_.next(line)) {
      line = trim(line);
      if (!line.empty()) return true;
    }
    return false;
  }

  std::string_view requireLine(std::string_view what) {
    std::string_view line;
    if (!nextLine(line)) reader_.fail("file ends in " + std::string(what));
    return line;
  }

  void expectEnd(std::string_view name) {
    const std::string end = "$End" + std::string(name);
    if (!equalsIgnoringCase(requireLine(name), end)) reader_.fail("expected " + end);
  }

  void skipSection(std::string_view name) {
    const std::string end = "$End" + std::string(name);
    while (!equalsIgnoringCase(requireLine(name), end)) {
    }
  }

  void readFormat() {
    const std::vector<std::string_view> t = splitWhitespace(requireLine("$MeshFormat"));
    if (t.size() != 3) reader_.fail("$MeshFormat needs version, file type and data size");
    const double version = parseDouble(t[0], reader_, "format version");
    if (std::floor(version) != 2)
      reader_.fail("Gmsh format " + std::string(t[0]) + " is not supported (save as version 2 ASCII)");
    if (parseInteger(t[1], reader_, "file type") != 0)
      reader_.fail("binary Gmsh files are not supported (save as version 2 ASCII)");
  }

  long long count(std::string_view what) {
    const long long n = parseInteger(requireLine(what), reader_, "count");
    if (n < 0 || n > std::numeric_limits<int>::max()) reader_.fail("bad count " + std::to_string(n));
    return n;
  }

  void readNodes() {
    if (haveNodes_) reader_.fail("second node section");
    haveNodes_ = true;
    const long long n = count("nodes");
    for (long long i = 0; i < n; ++i) {
      const std::vector<std::string_view> t = splitWhitespace(requireLine("nodes"));
      if (t.size() != 4) reader_.fail("node needs a number and 3 coordinates");
      const long long id = parseInteger(t[0], reader_, "node number");
      if (!nodeIndex_.try_emplace(id, static_cast<int>(i)).second)
        reader_.fail("node number " + std::to_string(id) + " used twice");
      for (int k = 1; k <= 3; ++k) xyz_.push_back(parseDouble(t[k], reader_, "node coordinate"));
    }
  }

  int vertex(std::string_view token) const {
    const long long id = parseInteger(token, reader_, "node number");
    const auto found = nodeIndex_.find(id);
    if (found == nodeIndex_.end()) reader_.fail("node " + std::to_string(id) + " is not in the node section");
    return found->second;
  }

  int nodesOfType(long long type) const {
    const auto found = kNodesPerType.find(type);
    if (found != kNodesPerType.end()) return found->second;
    const auto name = kTypeNames.find(type);
    reader_.fail("element type " + std::to_string(type) +
                 (name != kTypeNames.end() ? " (" + std::string(name->second) + ")" : std::string()) +
                 " is not supported (only tetrahedra and triangles, with points and lines skipped)");
  }

  // v1: number type physical elementary #nodes nodes...; v2: number type #tags tags... nodes...
  void readElements(bool version1) {
    if (!haveNodes_) reader_.fail("elements before nodes");
    if (haveElements_) reader_.fail("second element section");
    haveElements_ = true;
    const long long n = count("elements");
    for (long long i = 0; i < n; ++i) {
      const std::vector<std::string_view> t = splitWhitespace(requireLine("elements"));
      if (t.size() < 3) reader_.fail("element record too short");
      const long long type = parseInteger(t[1], reader_, "element type");
      const int nodes = nodesOfType(type);
      const long long tags = version1 ? 2 : parseInteger(t[2], reader_, "tag count");
      const std::size_t first = version1 ? 5 : 3 + static_cast<std::size_t>(std::clamp(tags, 0LL, 1LL << 20));
      if (tags < 0 || t.size() != first + nodes ||
          (version1 && parseInteger(t[4], reader_, "node count") != nodes))
        reader_.fail("element record has " + std::to_string(t.size()) + " numbers, which does not fit its type");
      if (type != kTriangle && type != kTetrahedron) continue;
      Elements& out = type == kTriangle ? triangles_ : tets_;
      const std::size_t tag0 = version1 ? 2 : 3;
      out.physical.push_back(tags > 0 ? static_cast<int>(parseInteger(t[tag0], reader_, "tag")) : 0);
      out.elementary.push_back(tags > 1 ? static_cast<int>(parseInteger(t[tag0 + 1], reader_, "tag")) : 0);
      for (int k = 0; k < nodes; ++k) out.vertices.push_back(vertex(t[first + k]));
    }
  }

  TetMesh build() const {
    const std::string& source = reader_.source();
    if (!haveNodes_) throw BadInput(source, "no node section ($Nodes or $NOD)");
    if (!haveElements_) throw BadInput(source, "no element section ($Elements or $ELM)");
    TetMesh mesh;
    mesh.V = detail::fromRows(xyz_, 3);
    mesh.T = detail::fromRows(tets_.vertices, 4);
    mesh.F = detail::fromRows(triangles_.vertices, 3);
    detail::addReferenceColumn(mesh.tetAttributes, kLabel, tets_.physical);
    detail::addReferenceColumn(mesh.tetAttributes, kRegion, tets_.elementary);
    detail::addReferenceColumn(mesh.faceAttributes, kLabel, triangles_.physical);
    detail::addReferenceColumn(mesh.faceAttributes, kRegion, triangles_.elementary);
    return mesh;
  }

  LineReader reader_;
  std::unordered_map<long long, int> nodeIndex_;  // node number in the file -> row of V
  std::vector<double> xyz_;                        // flattened #V by 3
  Elements triangles_, tets_;
  bool haveNodes_ = false, haveElements_ = false;
};

void appendElements(std::string& out, long long& number, int type, const Eigen::MatrixXi& elements,
                    const AttributeSet& attributes) {
  const Eigen::VectorXi physical = detail::referenceColumn(attributes, kLabel, elements.rows());
  const Eigen::VectorXi elementary = detail::referenceColumn(attributes, kRegion, elements.rows());
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    for (long long value : {++number, static_cast<long long>(type), 2LL, static_cast<long long>(physical(e)),
                            static_cast<long long>(elementary(e))}) {
      detail::appendInteger(out, value);
      out += ' ';
    }
    for (Eigen::Index c = 0; c < elements.cols(); ++c) {
      detail::appendInteger(out, elements(e, c) + 1LL);
      out += c + 1 < elements.cols() ? ' ' : '\n';
    }
  }
}

}  // namespace

TetMesh parseGmsh(std::string_view text, const std::string& source) {
  TetMesh mesh = GmshParser(text, source).parse();
  orientTetsPositively(mesh.V, mesh.T);
  mesh.validate(source);
  return mesh;
}

std::string formatGmsh(const TetMesh& mesh) {
  std::string out = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n";
  detail::appendInteger(out, mesh.V.rows());
  out += '\n';
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    detail::appendInteger(out, i + 1LL);
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      detail::appendReal(out, mesh.V(i, k));
    }
    out += '\n';
  }
  out += "$EndNodes\n$Elements\n";
  detail::appendInteger(out, mesh.F.rows() + mesh.T.rows());
  out += '\n';
  long long number = 0;
  appendElements(out, number, kTriangle, mesh.F, mesh.faceAttributes);
  appendElements(out, number, kTetrahedron, mesh.T, mesh.tetAttributes);
  out += "$EndElements\n";
  return out;
}

}  // namespace vesalius::io
