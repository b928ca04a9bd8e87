// TetGen .node/.ele/.face (mesh_formats.h), as described in the TetGen 1.5 manual, section 5.2.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <cmath>
#include <limits>
#include <vector>

namespace vesalius::io {

namespace {

constexpr const char* kAttribute = "attribute";
constexpr const char* kMarker = "marker";
constexpr long long kMaxColumns = 1 << 16;

// Records of one TetGen file: non-blank lines with "#" comments cut off, split into tokens.
class RecordReader {
 public:
  RecordReader(std::string_view text, const std::string& source) : reader_(text, source) {}

  // Next record, or false at the end. Remembers a SPACE=RAS tag seen in a comment.
  bool next(std::vector<std::string_view>& tokens) {
    std::string_view line;
    while (reader_.next(line)) {
      const std::size_t hash = line.find('#');
      if (hash != std::string_view::npos) ras_ = ras_ || findSpaceTag(line.substr(hash)) == SpaceTag::kRas;
      tokens = splitWhitespace(line.substr(0, hash));
      if (!tokens.empty()) return true;
    }
    return false;
  }

  // The record for element `i` of `count` (named `what`), which must have one of the token counts given.
  std::vector<std::string_view> record(long long i, long long count, const char* what, std::size_t size,
                                       std::size_t alternativeSize = 0) {
    std::vector<std::string_view> tokens;
    if (!next(tokens))
      throw BadInput(reader_.source(), "file ends after " + std::to_string(i) + " of " + std::to_string(count) + " " +
                                           what + "s");
    if (tokens.size() != size && tokens.size() != alternativeSize)
      fail(std::string(what) + " has " + std::to_string(tokens.size()) + " numbers, expected " + std::to_string(size));
    return tokens;
  }

  // The header record: 1 to maxFields integers, missing ones taken from `defaults`.
  std::vector<long long> header(std::vector<long long> defaults) {
    std::vector<std::string_view> tokens;
    if (!next(tokens)) throw BadInput(reader_.source(), "empty file");
    if (tokens.size() > defaults.size()) fail("header has " + std::to_string(tokens.size()) + " numbers");
    for (std::size_t i = 0; i < tokens.size(); ++i) defaults[i] = integer(tokens[i], "header number");
    for (long long value : defaults)
      if (value < 0 || value > std::numeric_limits<int>::max()) fail("bad header number " + std::to_string(value));
    return defaults;
  }

  long long integer(std::string_view token, const char* what) const { return parseInteger(token, reader_, what); }
  double real(std::string_view token, const char* what) const { return parseDouble(token, reader_, what); }
  [[noreturn]] void fail(const std::string& problem) const { reader_.fail(problem); }
  bool ras() const { return ras_; }

 private:
  LineReader reader_;
  bool ras_ = false;
};

struct Nodes {
  std::vector<double> xyz;         // flattened #V by 3
  std::vector<double> attributes;  // flattened #V by k
  std::vector<int> markers;        // #V (empty without markers)
  long long count = 0;
  int columns = 0;  // k
  long long base = 0;
  bool ras = false;
};

Nodes parseNodes(std::string_view text, const std::string& source) {
  RecordReader in(text, source);
  const std::vector<long long> h = in.header({0, 3, 0, 0});
  if (h[1] != 3) in.fail("dimension " + std::to_string(h[1]) + " (only 3 is supported)");
  if (h[2] > kMaxColumns || h[3] > 1) in.fail("bad header");
  Nodes nodes;
  nodes.count = h[0];
  nodes.columns = static_cast<int>(h[2]);
  const std::size_t reals = 3 + static_cast<std::size_t>(h[2]);
  for (long long i = 0; i < nodes.count; ++i) {
    const std::vector<std::string_view> t = in.record(i, nodes.count, "node", 1 + reals + h[3]);
    const long long index = in.integer(t[0], "node index");
    if (i == 0 && index != 0 && index != 1) in.fail("first node index is " + std::to_string(index) + ", not 0 or 1");
    if (i == 0) nodes.base = index;
    if (index != nodes.base + i) in.fail("node index " + std::to_string(index) + " out of sequence");
    for (std::size_t k = 1; k <= reals; ++k)
      (k < 4 ? nodes.xyz : nodes.attributes).push_back(in.real(t[k], k < 4 ? "coordinate" : "node attribute"));
    if (h[3]) nodes.markers.push_back(static_cast<int>(in.integer(t.back(), "boundary marker")));
  }
  nodes.ras = in.ras();
  return nodes;
}

// A 0-based vertex index from a node number in .ele or .face.
int nodeIndex(const RecordReader& in, std::string_view token, const Nodes& nodes) {
  const long long number = in.integer(token, "node number");
  if (number < nodes.base || number - nodes.base >= nodes.count)
    in.fail("node " + std::to_string(number) + " does not exist (the .node file has " + std::to_string(nodes.count) +
            " nodes numbered from " + std::to_string(nodes.base) + ")");
  return static_cast<int>(number - nodes.base);
}

int integralAttribute(const RecordReader& in, std::string_view token) {
  const double value = in.real(token, "region attribute");
  if (value != std::round(value) || std::abs(value) > std::numeric_limits<int>::max())
    in.fail("region attribute '" + std::string(token) + "' is not an integer");
  return static_cast<int>(value);
}

void parseElements(std::string_view text, const std::string& source, const Nodes& nodes, TetMesh& mesh) {
  RecordReader in(text, source);
  const std::vector<long long> h = in.header({0, 4, 0});
  if (h[1] != 4) in.fail(std::to_string(h[1]) + "-node tetrahedra (only 4-node tetrahedra are supported)");
  if (h[2] > kMaxColumns) in.fail("bad header");
  std::vector<int> tets, regions;
  std::vector<double> attributes;
  for (long long i = 0; i < h[0]; ++i) {
    const std::vector<std::string_view> t = in.record(i, h[0], "tetrahedron", 5 + h[2]);
    in.integer(t[0], "tetrahedron index");
    for (int k = 1; k <= 4; ++k) tets.push_back(nodeIndex(in, t[k], nodes));
    if (h[2] > 0) regions.push_back(integralAttribute(in, t[5]));
    for (std::size_t k = 6; k < t.size(); ++k) attributes.push_back(in.real(t[k], "tetrahedron attribute"));
  }
  mesh.T = detail::fromRows(tets, 4);
  detail::addReferenceColumn(mesh.tetAttributes, kRegion, regions);
  if (h[2] > 1)
    mesh.tetAttributes.real[kAttribute] = detail::fromRows(attributes, h[2] - 1);
}

void parseFaces(std::string_view text, const std::string& source, const Nodes& nodes, TetMesh& mesh) {
  RecordReader in(text, source);
  const std::vector<long long> h = in.header({0, 0});
  if (h[1] > 1) in.fail("bad header");
  std::vector<int> faces, markers;
  for (long long i = 0; i < h[0]; ++i) {
    // With -nn TetGen appends the two tets sharing the face; they are not kept.
    const std::vector<std::string_view> t = in.record(i, h[0], "face", 4 + h[1], 6 + h[1]);
    in.integer(t[0], "face index");
    for (int k = 1; k <= 3; ++k) faces.push_back(nodeIndex(in, t[k], nodes));
    if (h[1]) markers.push_back(static_cast<int>(in.integer(t[4], "boundary marker")));
  }
  mesh.F = detail::fromRows(faces, 3);
  detail::addReferenceColumn(mesh.faceAttributes, kMarker, markers);
}

void appendRecord(std::string& out, Eigen::Index index, const Eigen::RowVectorXd& reals,
                  const std::vector<long long>& integers) {
  detail::appendInteger(out, index + 1LL);
  for (Eigen::Index k = 0; k < reals.size(); ++k) {
    out += ' ';
    detail::appendReal(out, reals(k));
  }
  for (long long value : integers) {
    out += ' ';
    detail::appendInteger(out, value);
  }
  out += '\n';
}

std::string header(std::initializer_list<long long> numbers) {
  std::string out;
  for (long long n : numbers) {
    if (!out.empty()) out += ' ';
    detail::appendInteger(out, n);
  }
  return out + '\n';
}

std::string formatNodes(const TetMesh& mesh) {
  const auto found = mesh.vertexAttributes.real.find(kAttribute);
  const bool hasAttributes = found != mesh.vertexAttributes.real.end() && found->second.rows() == mesh.V.rows();
  const Eigen::MatrixXd attributes = hasAttributes ? found->second : Eigen::MatrixXd(mesh.V.rows(), 0);
  const bool hasMarkers = mesh.vertexAttributes.integer.count(kMarker) > 0;
  const Eigen::VectorXi markers = detail::referenceColumn(mesh.vertexAttributes, kMarker, mesh.V.rows());
  std::string out = "# TetGen nodes written by Vesalius, millimetres, SPACE=LPS\n" +
                    header({mesh.V.rows(), 3, attributes.cols(), hasMarkers ? 1 : 0});
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    Eigen::RowVectorXd reals(3 + attributes.cols());
    reals.head<3>() = mesh.V.row(i);
    if (attributes.cols() > 0) reals.tail(attributes.cols()) = attributes.row(i);  // row() of 0 columns is UB
    appendRecord(out, i, reals, hasMarkers ? std::vector<long long>{markers(i)} : std::vector<long long>{});
  }
  return out;
}

std::string formatElements(const TetMesh& mesh) {
  const auto found = mesh.tetAttributes.real.find(kAttribute);
  const bool hasAttributes = found != mesh.tetAttributes.real.end() && found->second.rows() == mesh.T.rows();
  const Eigen::MatrixXd attributes = hasAttributes ? found->second : Eigen::MatrixXd(mesh.T.rows(), 0);
  // The region is the first attribute; it is written (as 0 when absent) whenever attributes follow it.
  const bool hasRegion = mesh.tetAttributes.integer.count(kRegion) > 0 || hasAttributes;
  const Eigen::VectorXi regions = detail::referenceColumn(mesh.tetAttributes, kRegion, mesh.T.rows());
  std::string out = header({mesh.T.rows(), 4, (hasRegion ? 1 : 0) + attributes.cols()});
  for (Eigen::Index t = 0; t < mesh.T.rows(); ++t) {
    std::vector<long long> integers;
    for (int k = 0; k < 4; ++k) integers.push_back(mesh.T(t, k) + 1LL);
    if (hasRegion) integers.push_back(regions(t));
    detail::appendInteger(out, t + 1LL);
    for (long long value : integers) {
      out += ' ';
      detail::appendInteger(out, value);
    }
    for (Eigen::Index k = 0; k < attributes.cols(); ++k) {
      out += ' ';
      detail::appendReal(out, attributes(t, k));
    }
    out += '\n';
  }
  return out;
}

std::string formatFaces(const TetMesh& mesh) {
  const bool hasMarkers = mesh.faceAttributes.integer.count(kMarker) > 0;
  const Eigen::VectorXi markers = detail::referenceColumn(mesh.faceAttributes, kMarker, mesh.F.rows());
  std::string out = header({mesh.F.rows(), hasMarkers ? 1 : 0});
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    std::vector<long long> integers{mesh.F(f, 0) + 1LL, mesh.F(f, 1) + 1LL, mesh.F(f, 2) + 1LL};
    if (hasMarkers) integers.push_back(markers(f));
    appendRecord(out, f, Eigen::RowVectorXd(0), integers);
  }
  return out;
}

}  // namespace

TetMesh parseTetGen(std::string_view nodeText, std::string_view eleText, std::string_view faceText,
                    const std::string& source) {
  const Nodes nodes = parseNodes(nodeText, source + ".node");
  TetMesh mesh;
  mesh.V = detail::fromRows(nodes.xyz, 3);
  if (nodes.columns > 0)
    mesh.vertexAttributes.real[kAttribute] = detail::fromRows(nodes.attributes, nodes.columns);
  detail::addReferenceColumn(mesh.vertexAttributes, kMarker, nodes.markers);
  parseElements(eleText, source + ".ele", nodes, mesh);
  if (!faceText.empty()) parseFaces(faceText, source + ".face", nodes, mesh);
  if (nodes.ras) flipRasLps(mesh.V);
  orientTetsPositively(mesh.V, mesh.T);
  mesh.validate(source + ".ele");
  return mesh;
}

TetGenFiles formatTetGen(const TetMesh& mesh) {
  return {formatNodes(mesh), formatElements(mesh), mesh.F.rows() > 0 ? formatFaces(mesh) : std::string()};
}

}  // namespace vesalius::io
