// STL, ASCII and binary (mesh_formats.h). STL stores each triangle with its own three corners; the
// reader merges corners with exactly equal coordinates into shared vertices so the surface is connected.
// mergeCoincidentVertices, which does that, lives here and serves every surface reader (mesh_io.cpp).
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <Eigen/Geometry>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <unordered_map>
#include <vector>

namespace vesalius::io {

namespace {

constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kPreambleBytes = 84;  // header + uint32 triangle count
constexpr std::size_t kRecordBytes = 50;    // normal, 3 corners (12 float32) + uint16 attribute

struct CoordinateHash {
  std::size_t operator()(const std::array<double, 3>& key) const {
    std::size_t h = 0;
    for (double c : key) h = h * 1000003u ^ std::hash<double>()(c);
    return h;
  }
};

// Collects triangle corners, each its own vertex; mesh() shares corners with equal coordinates.
class CornerMerger {
 public:
  void addCorner(const Eigen::Vector3d& p) { coordinates_.insert(coordinates_.end(), p.data(), p.data() + 3); }

  TriMesh mesh() const {
    TriMesh mesh;
    mesh.V = detail::fromRows(coordinates_, 3);
    mesh.F.resize(mesh.V.rows() / 3, 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) mesh.F.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
    return mergeCoincidentVertices(mesh);
  }

 private:
  std::vector<double> coordinates_;
};

std::uint32_t readUint32(const char* bytes) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = value << 8 | static_cast<unsigned char>(bytes[i]);
  return value;
}

float readFloat32(const char* bytes) {
  const std::uint32_t bits = readUint32(bytes);
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

void appendUint32(std::string& out, std::uint32_t value) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(value >> (8 * i) & 0xff));
}

void appendFloat32(std::string& out, double value) {
  const float f = static_cast<float>(value);
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  appendUint32(out, bits);
}

bool startsWithWord(std::string_view text, std::string_view word) {
  text = trim(text);
  return text.substr(0, word.size()) == word &&
         (text.size() == word.size() || std::isspace(static_cast<unsigned char>(text[word.size()])));
}

// ASCII when the text starts with "solid" and its next line opens a facet or closes the solid; binary
// files whose header happens to start with "solid" fail the second test.
bool isAsciiStl(std::string_view bytes) {
  if (!startsWithWord(bytes, "solid")) return false;
  const std::size_t eol = bytes.find('\n');
  if (eol == std::string_view::npos) return false;
  const std::string_view rest = bytes.substr(eol + 1);
  return startsWithWord(rest, "facet") || startsWithWord(rest, "endsolid");
}

TriMesh parseBinaryStl(std::string_view bytes, const std::string& source) {
  if (bytes.size() < kPreambleBytes)
    throw BadInput(source, "not an ASCII STL and too short (" + std::to_string(bytes.size()) +
                               " bytes) for a binary STL");
  const std::uint64_t count = readUint32(bytes.data() + kHeaderBytes);
  const std::uint64_t expected = kPreambleBytes + kRecordBytes * count;
  if (bytes.size() != expected)
    throw BadInput(source, "binary STL of " + std::to_string(count) + " triangles should have " +
                               std::to_string(expected) + " bytes, but has " + std::to_string(bytes.size()) +
                               (bytes.size() < expected ? " (truncated)" : ""));
  CornerMerger merger;
  for (std::uint64_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + kPreambleBytes + kRecordBytes * t + 12;  // skip the normal
    for (int corner = 0; corner < 3; ++corner) {
      const char* p = record + 12 * corner;
      const Eigen::Vector3d x(readFloat32(p), readFloat32(p + 4), readFloat32(p + 8));
      if (!x.allFinite()) throw BadInput(source, "triangle " + std::to_string(t) + " has a non-finite coordinate");
      merger.addCorner(x);
    }
  }
  TriMesh mesh = merger.mesh();
  if (findSpaceTag(bytes.substr(0, kHeaderBytes)) == SpaceTag::kRas) flipRasLps(mesh.V);
  return mesh;
}

// Reads the ASCII STL grammar line by line: solid { facet normal / outer loop / 3 vertex / endloop /
// endfacet } endsolid, possibly several solids.
class AsciiStlParser {
 public:
  AsciiStlParser(std::string_view text, const std::string& source) : reader_(text, source) {}

  TriMesh parse() {
    std::string_view line;
    while (reader_.next(line)) {
      const std::vector<std::string_view> tokens = splitWhitespace(line);
      if (!tokens.empty()) step(tokens, line);
    }
    if (state_ != State::kOutside) reader_.fail("file ends inside a solid (truncated? no 'endsolid')");
    TriMesh mesh = merger_.mesh();
    if (ras_) flipRasLps(mesh.V);
    return mesh;
  }

 private:
  enum class State { kOutside, kSolid, kFacet, kLoop, kLoopDone };

  void expect(State state, std::string_view keyword) const {
    if (state_ != state) reader_.fail("unexpected '" + std::string(keyword) + "'");
  }

  void step(const std::vector<std::string_view>& tokens, std::string_view line) {
    const std::string_view keyword = tokens[0];
    if (keyword == "solid") {
      expect(State::kOutside, keyword);
      ras_ = ras_ || findSpaceTag(line) == SpaceTag::kRas;
      state_ = State::kSolid;
    } else if (keyword == "facet") {
      expect(State::kSolid, keyword);
      state_ = State::kFacet;
    } else if (keyword == "outer") {
      expect(State::kFacet, keyword);
      state_ = State::kLoop;
      corners_ = 0;
    } else if (keyword == "vertex") {
      expect(State::kLoop, keyword);
      addVertex(tokens);
    } else if (keyword == "endloop") {
      expect(State::kLoop, keyword);
      if (corners_ != 3) reader_.fail("facet with " + std::to_string(corners_) + " vertices (STL needs 3)");
      state_ = State::kLoopDone;
    } else if (keyword == "endfacet") {
      expect(State::kLoopDone, keyword);
      state_ = State::kSolid;
    } else if (keyword == "endsolid") {
      expect(State::kSolid, keyword);
      state_ = State::kOutside;
    } else {
      reader_.fail("unexpected '" + std::string(keyword) + "'");
    }
  }

  void addVertex(const std::vector<std::string_view>& tokens) {
    if (tokens.size() != 4) reader_.fail("'vertex' needs 3 coordinates");
    if (++corners_ > 3) reader_.fail("facet with more than 3 vertices (STL needs 3)");
    merger_.addCorner(Eigen::Vector3d(parseDouble(tokens[1], reader_, "vertex coordinate"),
                                      parseDouble(tokens[2], reader_, "vertex coordinate"),
                                      parseDouble(tokens[3], reader_, "vertex coordinate")));
  }

  LineReader reader_;
  CornerMerger merger_;
  State state_ = State::kOutside;
  int corners_ = 0;
  bool ras_ = false;
};

Eigen::Vector3d unitNormal(const TriMesh& mesh, Eigen::Index f) {
  const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

}  // namespace

TriMesh parseStl(std::string_view bytes, const std::string& source) {
  TriMesh mesh = isAsciiStl(bytes) ? AsciiStlParser(bytes, source).parse() : parseBinaryStl(bytes, source);
  mesh.validate(source);
  return mesh;
}

std::string formatStlBinary(const TriMesh& mesh, const std::string& destination) {
  // float32 holds magnitudes up to about 3.4e38; a cast beyond it gives infinity, which no reader takes.
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    for (int k = 0; k < 3; ++k)
      if (!(std::abs(mesh.V(v, k)) <= double(std::numeric_limits<float>::max())))
        throw BadInput(destination, "vertex " + std::to_string(v) + " has a coordinate beyond the float32 range "
                                    "of binary STL; write ASCII STL");
  std::string out = "SPACE=LPS binary STL written by Vesalius";
  out.resize(kHeaderBytes, ' ');
  out.reserve(kPreambleBytes + kRecordBytes * mesh.F.rows());
  appendUint32(out, static_cast<std::uint32_t>(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d n = unitNormal(mesh, f);
    for (int k = 0; k < 3; ++k) appendFloat32(out, n(k));
    for (int corner = 0; corner < 3; ++corner)
      for (int k = 0; k < 3; ++k) appendFloat32(out, mesh.V(mesh.F(f, corner), k));
    out.append(2, '\0');
  }
  return out;
}

std::string formatStlAscii(const TriMesh& mesh) {
  std::string out = "solid SPACE=LPS\n";
  auto appendVector = [&out](const Eigen::Vector3d& v) {
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      detail::appendReal(out, v(k));
    }
    out += '\n';
  };
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    out += "  facet normal";
    appendVector(unitNormal(mesh, f));
    out += "    outer loop\n";
    for (int corner = 0; corner < 3; ++corner) {
      out += "      vertex";
      appendVector(mesh.V.row(mesh.F(f, corner)));
    }
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid SPACE=LPS\n";
  return out;
}

TriMesh mergeCoincidentVertices(const TriMesh& mesh) {
  // Adding 0.0 turns -0.0 into +0.0, so the hash agrees with ==, which treats them as equal.
  std::unordered_map<std::array<double, 3>, int, CoordinateHash> index;
  index.reserve(static_cast<std::size_t>(mesh.V.rows()));
  Eigen::VectorXi merged(mesh.V.rows());  // old vertex -> new vertex
  std::vector<int> first;                 // new vertex -> its first old vertex
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    const std::array<double, 3> key{mesh.V(i, 0) + 0.0, mesh.V(i, 1) + 0.0, mesh.V(i, 2) + 0.0};
    const auto [it, inserted] = index.try_emplace(key, static_cast<int>(first.size()));
    if (inserted) first.push_back(static_cast<int>(i));
    merged(i) = it->second;
  }
  if (static_cast<Eigen::Index>(first.size()) == mesh.V.rows()) return mesh;

  const Eigen::Map<const Eigen::VectorXi> keep(first.data(), static_cast<Eigen::Index>(first.size()));
  TriMesh out;
  out.V = mesh.V(keep, Eigen::all);
  out.F = mesh.F.unaryExpr([&](int v) { return merged(v); });
  out.UV = mesh.UV;
  out.FUV = mesh.FUV;
  out.faceAttributes = mesh.faceAttributes;
  // A vertex attribute survives only if the merged points agree on it; values that differ (normals of
  // a cube written per face) were per corner and no single vertex value can stand for them.
  for (const auto& [name, values] : mesh.vertexAttributes.integer) {
    bool agree = true;
    for (Eigen::Index i = 0; agree && i < values.size(); ++i) agree = values(i) == values(first[merged(i)]);
    if (agree) out.vertexAttributes.integer[name] = values(keep);
  }
  for (const auto& [name, values] : mesh.vertexAttributes.real) {
    bool agree = true;
    for (Eigen::Index i = 0; agree && i < values.rows(); ++i)
      agree = values.row(i) == values.row(first[merged(i)]);
    if (agree) out.vertexAttributes.real[name] = values(keep, Eigen::all);
  }
  return out;
}

}  // namespace vesalius::io
