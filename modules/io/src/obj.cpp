// Wavefront OBJ (mesh_formats.h): v, vt, f (v, v/vt, v//vn, v/vt/vn, negative indices, polygons), g.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <charconv>
#include <unordered_map>
#include <vector>

namespace vesalius::io {

namespace {

constexpr const char* kGroup = "group";

struct Corner {
  int vertex;
  int uv;  // -1 when the corner has no texture coordinate
};

// The group id an integer group name stands for ("g 12" -> 12), as the writer writes them.
bool integerGroupName(const std::string& name, int& id) {
  const char* end = name.data() + name.size();
  const auto result = std::from_chars(name.data(), end, id);
  return !name.empty() && result.ec == std::errc() && result.ptr == end;
}

class ObjParser {
 public:
  ObjParser(std::string_view text, const std::string& source) : reader_(text, source) {}

  TriMesh parse() {
    std::string_view line;
    while (reader_.next(line)) {
      const std::vector<std::string_view> tokens = splitWhitespace(line);
      if (tokens.empty()) continue;
      const std::string_view keyword = tokens[0];
      if (keyword[0] == '#')
        ras_ = ras_ || findSpaceTag(line) == SpaceTag::kRas;
      else if (keyword == "v")
        addVertex(tokens);
      else if (keyword == "vt")
        addTextureCoordinate(tokens);
      else if (keyword == "f")
        addFace(tokens);
      else if (keyword == "g")
        startGroup(line);
      // Normals, materials, smoothing groups, objects, lines and free-form geometry carry nothing a
      // TriMesh holds, so every other statement is skipped.
    }
    return build();
  }

 private:
  void addVertex(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4) reader_.fail("'v' needs 3 coordinates");
    for (int k = 1; k <= 3; ++k) vertices_.push_back(parseDouble(tokens[k], reader_, "vertex coordinate"));
  }

  void addTextureCoordinate(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 2) reader_.fail("'vt' needs a coordinate");
    uvs_.push_back(parseDouble(tokens[1], reader_, "texture coordinate"));
    uvs_.push_back(tokens.size() > 2 ? parseDouble(tokens[2], reader_, "texture coordinate") : 0.0);
  }

  void startGroup(std::string_view line) {
    const std::string_view name = trim(trim(line).substr(1));
    group_ = name.empty() ? "default" : std::string(name);
    groupId_ = -1;
  }

  // An OBJ index (1-based, or negative counting back from the last element defined so far) as 0-based.
  int resolve(std::string_view token, std::size_t count, const char* what) const {
    const long long index = parseInteger(token, reader_, what);
    const long long resolved = index > 0 ? index - 1 : static_cast<long long>(count) + index;
    if (index == 0 || resolved < 0 || resolved >= static_cast<long long>(count))
      reader_.fail(std::string(what) + " " + std::string(token) + " out of range (" + std::to_string(count) +
                   " defined so far)");
    return static_cast<int>(resolved);
  }

  Corner parseCorner(std::string_view token) const {
    std::vector<std::string_view> parts;
    for (std::size_t start = 0;;) {
      const std::size_t slash = token.find('/', start);
      parts.push_back(token.substr(start, slash == std::string_view::npos ? slash : slash - start));
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
    if (parts.size() > 3) reader_.fail("bad face corner '" + std::string(token) + "'");
    Corner corner{resolve(parts[0], vertices_.size() / 3, "vertex index"), -1};
    if (parts.size() > 1 && !parts[1].empty()) corner.uv = resolve(parts[1], uvs_.size() / 2, "texture index");
    if (parts.size() > 2) parseInteger(parts[2], reader_, "normal index");
    return corner;
  }

  void addFace(const std::vector<std::string_view>& tokens) {
    if (tokens.size() < 4) reader_.fail("face with fewer than 3 vertices");
    std::vector<Corner> corners;
    for (std::size_t i = 1; i < tokens.size(); ++i) corners.push_back(parseCorner(tokens[i]));
    const bool hasUv = corners[0].uv >= 0;
    for (const Corner& c : corners)
      if ((c.uv >= 0) != hasUv) reader_.fail("face mixes corners with and without texture coordinates");
    int& firstLine = hasUv ? firstLineWithUv_ : firstLineWithoutUv_;
    if (!firstLine) firstLine = reader_.lineNumber();
    if (groupId_ < 0) groupId_ = groupIds_.try_emplace(group_, static_cast<int>(groupIds_.size())).first->second;
    // Fan triangulation from the first corner: exact for the convex polygons OBJ exporters write.
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      for (const Corner& c : {corners[0], corners[k], corners[k + 1]}) {
        faces_.push_back(c.vertex);
        faceUvs_.push_back(c.uv);
      }
      faceGroups_.push_back(groupId_);
    }
  }

  void addGroupAttribute(TriMesh& mesh) const {
    if (groupIds_.size() < 2) return;
    std::vector<int> idOfGroup(groupIds_.size());
    bool allIntegers = true;
    for (const auto& [name, index] : groupIds_) {
      int id = index;
      allIntegers = allIntegers && integerGroupName(name, id);
      idOfGroup[index] = id;
    }
    Eigen::VectorXi group(mesh.F.rows());
    for (Eigen::Index f = 0; f < group.size(); ++f)
      group(f) = allIntegers ? idOfGroup[faceGroups_[f]] : faceGroups_[f];
    mesh.faceAttributes.integer[kGroup] = group;
  }

  TriMesh build() const {
    const std::string& source = reader_.source();
    if (faces_.empty()) throw BadInput(source, "no faces ('f' lines)");
    if (firstLineWithUv_ && firstLineWithoutUv_)
      throw BadInput(source, "the face on line " + std::to_string(firstLineWithUv_) +
                                 " has texture coordinates but the face on line " +
                                 std::to_string(firstLineWithoutUv_) + " has none");
    TriMesh mesh;
    mesh.V = detail::fromRows(vertices_, 3);
    mesh.F = detail::fromRows(faces_, 3);
    if (firstLineWithUv_) {
      mesh.UV = detail::fromRows(uvs_, 2);
      mesh.FUV = detail::fromRows(faceUvs_, 3);
    }
    addGroupAttribute(mesh);
    if (ras_) flipRasLps(mesh.V);
    return mesh;
  }

  LineReader reader_;
  std::vector<double> vertices_, uvs_;    // flattened #V by 3, #UV by 2
  std::vector<int> faces_, faceUvs_;      // flattened #F by 3
  std::vector<int> faceGroups_;           // #F, index into groupIds_
  std::unordered_map<std::string, int> groupIds_;  // group name -> index in order of first face
  std::string group_ = "default";
  int groupId_ = -1;  // index of group_ once it has a face
  int firstLineWithUv_ = 0, firstLineWithoutUv_ = 0;
  bool ras_ = false;
};

void appendRow(std::string& out, const char* keyword, const Eigen::RowVectorXd& row) {
  out += keyword;
  for (Eigen::Index k = 0; k < row.size(); ++k) {
    out += ' ';
    detail::appendReal(out, row(k));
  }
  out += '\n';
}

void appendFace(std::string& out, const TriMesh& mesh, Eigen::Index f) {
  out += 'f';
  for (int c = 0; c < 3; ++c) {
    out += ' ';
    detail::appendInteger(out, mesh.F(f, c) + 1LL);
    if (mesh.FUV.rows() == mesh.F.rows() && mesh.FUV.rows() > 0) {
      out += '/';
      detail::appendInteger(out, mesh.FUV(f, c) + 1LL);
    }
  }
  out += '\n';
}

}  // namespace

TriMesh parseObj(std::string_view text, const std::string& source) {
  TriMesh mesh = ObjParser(text, source).parse();
  mesh.validate(source);
  return mesh;
}

std::string formatObj(const TriMesh& mesh) {
  std::string out = "# OBJ written by Vesalius, millimetres\n# SPACE=LPS\n";
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) appendRow(out, "v", mesh.V.row(i));
  for (Eigen::Index i = 0; i < mesh.UV.rows(); ++i) appendRow(out, "vt", mesh.UV.row(i));
  const auto group = mesh.faceAttributes.integer.find(kGroup);
  const bool grouped = group != mesh.faceAttributes.integer.end() && group->second.rows() == mesh.F.rows();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    if (grouped && (f == 0 || group->second(f) != group->second(f - 1))) {
      out += "g ";
      detail::appendInteger(out, group->second(f));
      out += '\n';
    }
    appendFace(out, mesh, f);
  }
  return out;
}

}  // namespace vesalius::io
