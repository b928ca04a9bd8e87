// Binary glTF 2.0 (gltf.h). Written by hand rather than through a library: we need one small, fixed
// layout, and a reader that checks every offset of a file we did not write.
#include "vesalius/io/gltf.h"

#include "vesalius/core/error.h"
#include "vesalius/io/text_file.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

namespace vesalius::io {

namespace {

using OrderedJson = nlohmann::ordered_json;
using Json = nlohmann::json;

constexpr std::uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr std::size_t kHeaderBytes = 12, kChunkHeaderBytes = 8;
constexpr int kFloat = 5126, kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;
// Meshes may be instanced by several nodes; geometry read beyond this multiple of the file size is refused
// so a small hostile file cannot make us allocate without bound.
constexpr std::size_t kMaxExpansion = 16;

// glTF from LPS is this rotation (det +1) times 0.001; see gltf.h.
Eigen::Matrix3d gltfRotation() {
  Eigen::Matrix3d r;
  r << 1, 0, 0,  //
      0, 0, 1,   //
      0, -1, 0;
  return r;
}

void putU32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(char((v >> (8 * k)) & 0xFF));
}

std::uint32_t getU32(std::string_view bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v |= std::uint32_t(static_cast<unsigned char>(bytes[at + k])) << (8 * k);
  return v;
}

template <class T>
void appendRaw(std::string& bin, const std::vector<T>& values) {
  const std::size_t at = bin.size();
  bin.resize(at + values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(&bin[at], values.data(), values.size() * sizeof(T));
  while (bin.size() % 4 != 0) bin.push_back('\0');
}

// Area-weighted vertex normals in glTF axes (the un-normalised face cross products summed), unit length; a
// vertex on no triangle of positive area gets +Y, since the spec requires unit normals.
MatrixX3d gltfVertexNormals(const TriMesh& mesh) {
  MatrixX3d n = MatrixX3d::Zero(mesh.V.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    const Eigen::RowVector3d cross = (gltfRotation() * (b - a).cross(c - a)).transpose();
    for (int k = 0; k < 3; ++k) n.row(mesh.F(f, k)) += cross;
  }
  for (Eigen::Index v = 0; v < n.rows(); ++v) {
    const double length = n.row(v).norm();
    if (length > 0 && std::isfinite(length))
      n.row(v) /= length;
    else
      n.row(v) = Eigen::RowVector3d(0, 1, 0);
  }
  return n;
}

// ---- reading helpers: every value of the JSON is checked before it is used ----

class GlbReader {
 public:
  GlbReader(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  std::vector<GltfMesh> read();

 private:
  struct Accessor {
    const char* data = nullptr;  // first element
    std::size_t count = 0, stride = 0;
    int componentType = 0;
  };

  [[noreturn]] void fail(const std::string& problem) const { throw BadInput(source_, problem); }

  const Json& array(const Json& object, const char* key) const {
    static const Json kEmpty = Json::array();
    const auto it = object.find(key);
    if (it == object.end()) return kEmpty;
    if (!it->is_array()) fail(std::string("'") + key + "' is not an array");
    return *it;
  }
  std::uint64_t unsignedValue(const Json& value, const std::string& what) const {
    if (!value.is_number_integer() || (!value.is_number_unsigned() && value.get<std::int64_t>() < 0))
      fail(what + " is not a non-negative integer");
    return value.get<std::uint64_t>();
  }
  std::uint64_t unsignedMember(const Json& object, const char* key, const std::string& what,
                               std::uint64_t fallback) const {
    const auto it = object.find(key);
    return it == object.end() ? fallback : unsignedValue(*it, what + " " + key);
  }
  std::size_t index(const Json& value, std::size_t limit, const std::string& what) const {
    const std::uint64_t i = unsignedValue(value, what);
    if (i >= limit) fail(what + " " + std::to_string(i) + " is out of range (" + std::to_string(limit) + " defined)");
    return std::size_t(i);
  }
  double number(const Json& value, const std::string& what) const {
    if (!value.is_number() || !std::isfinite(value.get<double>())) fail(what + " is not a finite number");
    return value.get<double>();
  }

  void chunks();
  void buffers();
  Accessor accessor(std::size_t i, const std::string& type, std::initializer_list<int> componentTypes);
  Eigen::Matrix4d localTransform(const Json& node, std::size_t i) const;
  void primitive(const Json& p, const std::string& what, TriMesh& mesh, std::array<double, 4>& rgba, bool first);
  GltfMesh nodeMesh(std::size_t node, const Eigen::Matrix4d& transform);
  void charge(std::size_t bytes);

  std::string_view bytes_;
  const std::string& source_;
  Json doc_;
  std::string_view bin_;
  bool hasBin_ = false;
  std::vector<std::string_view> buffers_;
  std::size_t budget_ = 0;
};

void GlbReader::chunks() {
  if (bytes_.size() < kHeaderBytes) fail("too short for a GLB header (" + std::to_string(bytes_.size()) + " bytes)");
  if (getU32(bytes_, 0) != kMagic) fail("not a binary glTF file (no 'glTF' magic)");
  const std::uint32_t version = getU32(bytes_, 4);
  if (version != 2) fail("glTF container version " + std::to_string(version) + "; only version 2 is read");
  const std::uint32_t length = getU32(bytes_, 8);
  if (length > bytes_.size())
    fail("header says " + std::to_string(length) + " bytes, the file has " + std::to_string(bytes_.size()) +
         " (truncated)");
  const std::string_view file = bytes_.substr(0, length);
  budget_ = kMaxExpansion * file.size();
  std::size_t at = kHeaderBytes;
  bool first = true;
  std::string_view json;
  while (at < file.size()) {
    if (file.size() - at < kChunkHeaderBytes) fail("chunk header at byte " + std::to_string(at) + " is cut off");
    const std::uint32_t chunkLength = getU32(file, at), type = getU32(file, at + 4);
    at += kChunkHeaderBytes;
    if (chunkLength > file.size() - at)
      fail("chunk at byte " + std::to_string(at - kChunkHeaderBytes) + " says " + std::to_string(chunkLength) +
           " bytes, past the end of the file");
    const std::string_view data = file.substr(at, chunkLength);
    if (first && type != kChunkJson) fail("the first chunk is not JSON");
    if (first) json = data;
    else if (type == kChunkBin && !hasBin_) {
      bin_ = data;
      hasBin_ = true;
    }  // other chunk types are skipped, as the spec asks
    first = false;
    at += chunkLength;
  }
  if (first) fail("no JSON chunk");
  doc_ = Json::parse(json.begin(), json.end(), nullptr, false);
  if (doc_.is_discarded()) fail("the JSON chunk is not valid JSON");
  if (!doc_.is_object()) fail("the JSON chunk is not a JSON object");
}

void GlbReader::buffers() {
  const Json& list = array(doc_, "buffers");
  for (std::size_t b = 0; b < list.size(); ++b) {
    const Json& buffer = list[b];
    const std::string what = "buffer " + std::to_string(b);
    if (!buffer.is_object()) fail(what + " is not an object");
    if (buffer.contains("uri"))
      fail(what + " refers to an external file or data URI (only the GLB's own BIN chunk is read)");
    if (b != 0 || !hasBin_) fail(what + " has no data (a GLB holds one BIN chunk, for buffer 0)");
    const std::uint64_t length = unsignedMember(buffer, "byteLength", what, std::uint64_t(-1));
    if (length > bin_.size())
      fail(what + " byteLength " + std::to_string(length) + " is larger than the BIN chunk (" +
           std::to_string(bin_.size()) + " bytes)");
    buffers_.push_back(bin_.substr(0, std::size_t(length)));
  }
}

void GlbReader::charge(std::size_t bytes) {
  if (bytes > budget_)
    fail("nodes reuse meshes too often (more than " + std::to_string(kMaxExpansion) +
         " times the file's size of geometry)");
  budget_ -= bytes;
}

GlbReader::Accessor GlbReader::accessor(std::size_t i, const std::string& type,
                                        std::initializer_list<int> componentTypes) {
  const std::string what = "accessor " + std::to_string(i);
  const Json& a = array(doc_, "accessors")[i];
  if (!a.is_object()) fail(what + " is not an object");
  if (a.contains("sparse")) fail(what + " is sparse, which is not read");
  if (!a.contains("bufferView")) fail(what + " has no bufferView");
  if (!a.contains("type") || !a["type"].is_string() || a["type"].get<std::string>() != type)
    fail(what + " is not of type " + type);
  if (!a.contains("componentType")) fail(what + " has no componentType");
  const std::uint64_t componentType = unsignedValue(a["componentType"], what + " componentType");
  if (std::find(componentTypes.begin(), componentTypes.end(), int(componentType)) == componentTypes.end())
  {
    std::string allowed;
    for (const int t : componentTypes) allowed += (allowed.empty() ? "" : ", ") + std::to_string(t);
    fail(what + " componentType " + std::to_string(componentType) + " is not one this reader takes here (" +
         allowed + ")");
  }
  const std::size_t componentBytes = componentType == kUnsignedByte ? 1 : componentType == kUnsignedShort ? 2 : 4;
  const std::size_t elementBytes = componentBytes * (type == "VEC3" ? 3 : 1);
  const std::uint64_t count = unsignedMember(a, "count", what, 0);
  if (count == 0) fail(what + " has no elements");
  const std::uint64_t offset = unsignedMember(a, "byteOffset", what, 0);

  const std::size_t viewIndex = index(a["bufferView"], array(doc_, "bufferViews").size(), what + " bufferView");
  const std::string viewWhat = "bufferView " + std::to_string(viewIndex);
  const Json& view = doc_["bufferViews"][viewIndex];
  if (!view.is_object()) fail(viewWhat + " is not an object");
  if (!view.contains("buffer")) fail(viewWhat + " has no buffer");
  const std::size_t bufferIndex = index(view["buffer"], buffers_.size(), viewWhat + " buffer");
  const std::string_view buffer = buffers_[bufferIndex];
  const std::uint64_t viewOffset = unsignedMember(view, "byteOffset", viewWhat, 0);
  if (!view.contains("byteLength")) fail(viewWhat + " has no byteLength");
  const std::uint64_t viewLength = unsignedValue(view["byteLength"], viewWhat + " byteLength");
  if (viewOffset > buffer.size() || viewLength > buffer.size() - viewOffset)
    fail(viewWhat + " (offset " + std::to_string(viewOffset) + ", length " + std::to_string(viewLength) +
         ") lies beyond its buffer (" + std::to_string(buffer.size()) + " bytes)");
  const std::uint64_t stride = unsignedMember(view, "byteStride", viewWhat, elementBytes);
  if (stride < elementBytes || stride > 252) fail(viewWhat + " byteStride " + std::to_string(stride) + " is invalid");
  // The last element must end inside the view; written without products that could overflow.
  if (offset > viewLength || viewLength - offset < elementBytes ||
      count - 1 > (viewLength - offset - elementBytes) / stride)
    fail(what + " (" + std::to_string(count) + " elements from byte " + std::to_string(offset) +
         ") lies beyond " + viewWhat + " (" + std::to_string(viewLength) + " bytes)");
  charge(std::size_t(count) * elementBytes);
  Accessor out;
  out.data = buffer.data() + viewOffset + offset;
  out.count = std::size_t(count);
  out.stride = std::size_t(stride);
  out.componentType = int(componentType);
  return out;
}

Eigen::Matrix4d GlbReader::localTransform(const Json& node, std::size_t i) const {
  const std::string what = "node " + std::to_string(i);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  auto numbers = [&](const char* key, std::size_t n) {
    std::vector<double> values;
    const auto it = node.find(key);
    if (it == node.end()) return values;
    if (!it->is_array() || it->size() != n) fail(what + " " + key + " is not " + std::to_string(n) + " numbers");
    for (const Json& v : *it) values.push_back(number(v, what + " " + key));
    return values;
  };
  const std::vector<double> matrix = numbers("matrix", 16);
  if (!matrix.empty()) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = matrix[std::size_t(4 * c + r)];  // column-major
    return m;
  }
  const std::vector<double> t = numbers("translation", 3), q = numbers("rotation", 4), s = numbers("scale", 3);
  if (!q.empty()) {
    Eigen::Quaterniond rotation(q[3], q[0], q[1], q[2]);  // stored x, y, z, w
    if (rotation.norm() < 1e-12) fail(what + " rotation is not a unit quaternion");
    m.topLeftCorner<3, 3>() = rotation.normalized().toRotationMatrix();
  }
  if (!s.empty()) m.topLeftCorner<3, 3>() = m.topLeftCorner<3, 3>() * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal();
  if (!t.empty()) m.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
  return m;
}

void GlbReader::primitive(const Json& p, const std::string& what, TriMesh& mesh, std::array<double, 4>& rgba,
                          bool first) {
  if (!p.is_object()) fail(what + " is not an object");
  if (p.contains("mode")) {
    const std::uint64_t mode = unsignedValue(p["mode"], what + " mode");
    if (mode != kTriangles) fail(what + " has mode " + std::to_string(mode) + " (only triangles, mode 4, are read)");
  }
  if (!p.contains("attributes") || !p["attributes"].is_object() || !p["attributes"].contains("POSITION"))
    fail(what + " has no POSITION attribute");
  const std::size_t accessors = array(doc_, "accessors").size();
  const Accessor positions =
      accessor(index(p["attributes"]["POSITION"], accessors, what + " POSITION"), "VEC3", {kFloat});
  const Eigen::Index base = mesh.V.rows();
  if (positions.count > std::size_t(std::numeric_limits<int>::max()) - std::size_t(base))
    fail(what + " has too many vertices");
  mesh.V.conservativeResize(base + Eigen::Index(positions.count), 3);
  for (std::size_t v = 0; v < positions.count; ++v) {
    float xyz[3];
    std::memcpy(xyz, positions.data + v * positions.stride, sizeof xyz);
    mesh.V.row(base + Eigen::Index(v)) << xyz[0], xyz[1], xyz[2];
  }

  std::vector<std::uint32_t> corners;
  if (p.contains("indices")) {
    const Accessor indices =
        accessor(index(p["indices"], accessors, what + " indices"), "SCALAR",
                 {kUnsignedByte, kUnsignedShort, kUnsignedInt});
    corners.resize(indices.count);
    for (std::size_t k = 0; k < indices.count; ++k) {
      const char* at = indices.data + k * indices.stride;
      if (indices.componentType == kUnsignedByte) {
        corners[k] = static_cast<unsigned char>(*at);
      } else if (indices.componentType == kUnsignedShort) {
        std::uint16_t value;
        std::memcpy(&value, at, sizeof value);
        corners[k] = value;
      } else {
        std::memcpy(&corners[k], at, sizeof corners[k]);
      }
      if (corners[k] >= positions.count)
        fail(what + " index " + std::to_string(corners[k]) + " is beyond its " + std::to_string(positions.count) +
             " vertices");
    }
  } else {
    corners.resize(positions.count);
    for (std::size_t k = 0; k < corners.size(); ++k) corners[k] = std::uint32_t(k);
  }
  if (corners.size() % 3 != 0) fail(what + " has " + std::to_string(corners.size()) + " corners, not a multiple of 3");
  const Eigen::Index faceBase = mesh.F.rows();
  mesh.F.conservativeResize(faceBase + Eigen::Index(corners.size() / 3), 3);
  for (std::size_t k = 0; k < corners.size(); ++k)
    mesh.F(faceBase + Eigen::Index(k / 3), Eigen::Index(k % 3)) = int(base) + int(corners[k]);

  if (first && p.contains("material")) {
    const std::size_t m = index(p["material"], array(doc_, "materials").size(), what + " material");
    const Json& material = doc_["materials"][m];
    const std::string materialWhat = "material " + std::to_string(m);
    if (!material.is_object()) fail(materialWhat + " is not an object");
    const auto pbr = material.find("pbrMetallicRoughness");
    if (pbr != material.end() && pbr->is_object() && pbr->contains("baseColorFactor")) {
      const Json& factor = (*pbr)["baseColorFactor"];
      if (!factor.is_array() || factor.size() != 4) fail(materialWhat + " baseColorFactor is not 4 numbers");
      for (std::size_t k = 0; k < 4; ++k) rgba[k] = number(factor[k], materialWhat + " baseColorFactor");
    }
  }
}

GltfMesh GlbReader::nodeMesh(std::size_t n, const Eigen::Matrix4d& transform) {
  const Json& node = doc_["nodes"][n];
  const std::size_t m = index(node["mesh"], array(doc_, "meshes").size(), "node " + std::to_string(n) + " mesh");
  const Json& mesh = doc_["meshes"][m];
  const std::string what = "mesh " + std::to_string(m);
  if (!mesh.is_object()) fail(what + " is not an object");
  GltfMesh out;
  if (node.contains("name") && node["name"].is_string())
    out.name = node["name"].get<std::string>();
  else if (mesh.contains("name") && mesh["name"].is_string())
    out.name = mesh["name"].get<std::string>();
  else
    out.name = "node " + std::to_string(n);
  const Json& primitives = array(mesh, "primitives");
  if (primitives.empty()) fail(what + " has no primitives");
  TriMesh gltf;
  for (std::size_t p = 0; p < primitives.size(); ++p)
    primitive(primitives[p], what + " primitive " + std::to_string(p), gltf, out.rgba, p == 0);

  const Eigen::Matrix3d linear = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d shift = transform.topRightCorner<3, 1>();
  out.mesh.V.resize(gltf.V.rows(), 3);
  for (Eigen::Index v = 0; v < gltf.V.rows(); ++v)
    out.mesh.V.row(v) = lpsFromGltf(linear * gltf.V.row(v).transpose() + shift).transpose();
  out.mesh.F = gltf.F;
  // A mirroring transform reverses the winding (spec §3.7.2.1), so swap two corners to keep outward normals.
  if (linear.determinant() < 0) out.mesh.F.col(1).swap(out.mesh.F.col(2));
  try {
    out.mesh.validate(source_);
  } catch (const BadInput& e) {
    fail("node '" + out.name + "': " + e.problem());
  }
  return out;
}

std::vector<GltfMesh> GlbReader::read() {
  chunks();
  try {
    const Json& required = array(doc_, "extensionsRequired");
    if (!required.empty())
      fail("requires the extension " + (required[0].is_string() ? required[0].get<std::string>() : std::string("?")) +
           ", which is not read");
    buffers();
    const Json& nodes = array(doc_, "nodes");
    for (std::size_t n = 0; n < nodes.size(); ++n)
      if (!nodes[n].is_object()) fail("node " + std::to_string(n) + " is not an object");

    // The roots: the default scene's nodes, or every node that is nobody's child when there is no scene.
    std::vector<std::size_t> roots;
    const Json& scenes = array(doc_, "scenes");
    if (!scenes.empty()) {
      const std::size_t s = doc_.contains("scene") ? index(doc_["scene"], scenes.size(), "scene") : 0;
      if (!scenes[s].is_object()) fail("scene " + std::to_string(s) + " is not an object");
      for (const Json& r : array(scenes[s], "nodes")) roots.push_back(index(r, nodes.size(), "scene node"));
    } else {
      std::vector<bool> child(nodes.size(), false);
      for (std::size_t n = 0; n < nodes.size(); ++n)
        for (const Json& c : array(nodes[n], "children")) child[index(c, nodes.size(), "child node")] = true;
      for (std::size_t n = 0; n < nodes.size(); ++n)
        if (!child[n]) roots.push_back(n);
    }

    // Depth first with an explicit stack (a deep hostile tree must not exhaust the call stack); a node met
    // twice means a cycle or a shared child, which the spec forbids.
    std::vector<GltfMesh> out;
    std::vector<bool> seen(nodes.size(), false);
    std::vector<std::pair<std::size_t, Eigen::Matrix4d>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, Eigen::Matrix4d::Identity());
    while (!stack.empty()) {
      const auto [n, parent] = stack.back();
      stack.pop_back();
      if (seen[n]) fail("node " + std::to_string(n) + " appears twice in the node tree");
      seen[n] = true;
      const Eigen::Matrix4d transform = parent * localTransform(nodes[n], n);
      if (nodes[n].contains("mesh")) out.push_back(nodeMesh(n, transform));
      const Json& children = array(nodes[n], "children");
      for (auto c = children.rbegin(); c != children.rend(); ++c)
        stack.emplace_back(index(*c, nodes.size(), "node " + std::to_string(n) + " child"), transform);
    }
    if (out.empty()) fail("no node with a mesh");
    return out;
  } catch (const Json::exception& e) {
    fail(std::string("malformed glTF JSON: ") + e.what());
  }
}

}  // namespace

Eigen::Vector3d gltfFromLps(const Eigen::Vector3d& lpsMm) { return 0.001 * (gltfRotation() * lpsMm); }

Eigen::Vector3d lpsFromGltf(const Eigen::Vector3d& gltfMetres) {
  return 1000.0 * (gltfRotation().transpose() * gltfMetres);
}

std::array<double, 4> linearRgba(const DisplayColour& srgb, double alpha) {
  std::array<double, 4> out{0, 0, 0, alpha};
  for (int k = 0; k < 3; ++k) {
    const double c = srgb[std::size_t(k)] / 255.0;
    out[std::size_t(k)] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  }
  return out;
}

std::string formatGlb(const std::vector<GltfNode>& nodes, const std::string& source) {
  if (nodes.empty()) throw BadInput(source, "no node to write");
  OrderedJson accessors = OrderedJson::array(), views = OrderedJson::array(), meshes = OrderedJson::array(),
              materials = OrderedJson::array(), gltfNodes = OrderedJson::array(), sceneNodes = OrderedJson::array();
  std::string bin;
  auto addView = [&](std::size_t offset, int target) {
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bin.size() - offset}, {"target", target}});
    return views.size() - 1;
  };

  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const GltfNode& node = nodes[i];
    const std::string what = "node '" + node.name + "'";
    if (node.mesh == nullptr || node.mesh->F.rows() == 0) throw BadInput(source, what + " has no triangles");
    const TriMesh& mesh = *node.mesh;
    try {
      mesh.validate(source);
    } catch (const BadInput& e) {
      throw BadInput(source, what + ": " + e.problem());
    }
    for (const double c : node.rgba)
      if (!(c >= 0 && c <= 1)) throw BadInput(source, what + " has a colour component outside 0..1");

    const Eigen::Index nv = mesh.V.rows();
    std::vector<float> positions(std::size_t(nv) * 3), normals(std::size_t(nv) * 3);
    const MatrixX3d n = gltfVertexNormals(mesh);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::infinity()), hi = -lo;
    for (Eigen::Index v = 0; v < nv; ++v) {
      const Eigen::Vector3d metres = gltfFromLps(mesh.V.row(v).transpose());
      if (metres.cwiseAbs().maxCoeff() > std::numeric_limits<float>::max())  // the float cast would be undefined
        throw BadInput(source, what + " has a vertex beyond float32 range in metres");
      const Eigen::Vector3f p = metres.cast<float>();
      const Eigen::Vector3f d = n.row(v).transpose().cast<float>();
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
      for (int k = 0; k < 3; ++k) {
        positions[std::size_t(3 * v + k)] = p(k);
        normals[std::size_t(3 * v + k)] = d(k);
      }
    }
    std::vector<std::uint32_t> indices(std::size_t(mesh.F.rows()) * 3);
    for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) indices[std::size_t(3 * f + k)] = std::uint32_t(mesh.F(f, k));

    std::size_t at = bin.size();
    appendRaw(bin, positions);
    const std::size_t positionView = addView(at, kArrayBuffer);
    at = bin.size();
    appendRaw(bin, normals);
    const std::size_t normalView = addView(at, kArrayBuffer);
    at = bin.size();
    appendRaw(bin, indices);
    const std::size_t indexView = addView(at, kElementArrayBuffer);

    const std::size_t a = accessors.size();
    accessors.push_back({{"bufferView", positionView}, {"componentType", kFloat}, {"count", nv}, {"type", "VEC3"},
                         {"min", {lo(0), lo(1), lo(2)}}, {"max", {hi(0), hi(1), hi(2)}}});
    accessors.push_back({{"bufferView", normalView}, {"componentType", kFloat}, {"count", nv}, {"type", "VEC3"}});
    accessors.push_back(
        {{"bufferView", indexView}, {"componentType", kUnsignedInt}, {"count", indices.size()}, {"type", "SCALAR"}});
    materials.push_back({{"name", node.name},
                         {"pbrMetallicRoughness",
                          {{"baseColorFactor", node.rgba}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
                         {"alphaMode", node.rgba[3] < 1 ? "BLEND" : "OPAQUE"},
                         {"doubleSided", false}});
    meshes.push_back({{"name", node.name},
                      {"primitives",
                       {{{"attributes", {{"POSITION", a}, {"NORMAL", a + 1}}},
                         {"indices", a + 2},
                         {"material", i},
                         {"mode", kTriangles}}}}});
    gltfNodes.push_back({{"name", node.name}, {"mesh", i}});
    sceneNodes.push_back(i);
  }

  OrderedJson doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "Vesalius"}};
  doc["scene"] = 0;
  doc["scenes"] = {{{"nodes", sceneNodes}}};
  doc["nodes"] = gltfNodes;
  doc["meshes"] = meshes;
  doc["materials"] = materials;
  doc["accessors"] = accessors;
  doc["bufferViews"] = views;
  doc["buffers"] = {{{"byteLength", bin.size()}}};
  // Names that are not UTF-8 are written with U+FFFD rather than failing the whole model.
  std::string json = doc.dump(-1, ' ', false, OrderedJson::error_handler_t::replace);
  while (json.size() % 4 != 0) json.push_back(' ');

  const std::uint64_t total = kHeaderBytes + 2 * kChunkHeaderBytes + json.size() + bin.size();
  if (total > std::numeric_limits<std::uint32_t>::max())
    throw BadInput(source, "the model is larger than the 4 GiB a GLB file can hold");
  std::string out;
  out.reserve(std::size_t(total));
  putU32(out, kMagic);
  putU32(out, 2);
  putU32(out, std::uint32_t(total));
  putU32(out, std::uint32_t(json.size()));
  putU32(out, kChunkJson);
  out += json;
  putU32(out, std::uint32_t(bin.size()));
  putU32(out, kChunkBin);
  out += bin;
  return out;
}

std::vector<GltfMesh> parseGlb(std::string_view bytes, const std::string& source) {
  return GlbReader(bytes, source).read();
}

void writeGlb(const std::string& path, const std::vector<GltfNode>& nodes, const WriteOptions& options) {
  const std::string bytes = formatGlb(nodes, path);
  writeAtomically(path, options, [&](const std::string& temporary) { writeFileBytes(temporary, bytes); });
}

std::vector<GltfMesh> readGlb(const std::string& path) { return parseGlb(readBinaryFile(path), path); }

void writeAnatomyGlb(const std::string& path, const ReferenceAnatomy& anatomy, const WriteOptions& options,
                     double skinAlpha) {
  std::vector<GltfNode> nodes;
  for (const ReferenceTissue& tissue : anatomy.tissues)
    nodes.push_back({tissue.name, &tissue.mesh, linearRgba(tissueKindColour(tissue.kind), 1.0)});
  nodes.push_back({"skin", &anatomy.skin, linearRgba(kSkinColour, skinAlpha)});
  writeGlb(path, nodes, options);
}

}  // namespace vesalius::io
