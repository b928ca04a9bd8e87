// Gmsh .msh: version 1 ($NOD/$ELM), version 2 ASCII and version 4.1 ASCII, as described in the Gmsh
// reference manual ("MSH file format" for 4.1, "Legacy formats" for 1 and 2).
//
// In 4.1 nodes and elements come in blocks, one per model entity (point, curve, surface, volume), and an
// element's physical group is that of its entity, listed in $Entities. An entity in several physical
// groups gives its elements the first one (v2 files repeat such elements once per group instead). The
// writer makes one entity per (elementary tag, physical tag) pair of each dimension and puts every node
// in the block of the first entity of the highest dimension, which Gmsh reads; entity bounding boxes
// are written, bounding entities (topology we do not have) are not.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <initializer_list>
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
  std::vector<long long> tags;  // element tags (4.1 only)

  // Puts the elements in the order of their tags (stable). A 4.1 file groups elements by entity, so
  // this, not the block order, is the order the writer had (ours numbers them in mesh order).
  void sortByTag() {
    std::vector<std::size_t> order(tags.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tags[a] < tags[b]; });
    const std::size_t k = tags.empty() ? 0 : vertices.size() / tags.size();
    Elements sorted;
    for (std::size_t i : order) {
      sorted.vertices.insert(sorted.vertices.end(), vertices.begin() + i * k, vertices.begin() + (i + 1) * k);
      sorted.physical.push_back(physical[i]);
      sorted.elementary.push_back(elementary[i]);
    }
    vertices.swap(sorted.vertices);
    physical.swap(sorted.physical);
    elementary.swap(sorted.elementary);
  }
};

class GmshParser {
 public:
  GmshParser(std::string_view text, const std::string& source) : reader_(text, source), textSize_(text.size()) {}

  TetMesh parse() {
    std::string_view line;
    while (nextLine(line)) {
      if (line[0] != '$') reader_.fail("expected a section such as $Nodes, found '" + std::string(line) + "'");
      const std::string_view name = line.substr(1);
      if (equalsIgnoringCase(name, "MeshFormat"))
        readFormat();
      else if (name == "Entities" && version4_)
        readEntities();
      else if (name == "Nodes" && version4_)
        readNodes4();
      else if (name == "Elements" && version4_)
        readElements4();
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
    if (next_ < tokens_.size())
      reader_.fail("unexpected '" + std::string(tokens_[next_]) + "' (more numbers than the counts say)");
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
    version4_ = version == 4.1;
    if (std::floor(version) != 2 && !version4_)
      reader_.fail("Gmsh format " + std::string(t[0]) + " is not supported (save as version 4.1 or 2.2 ASCII)");
    if (parseInteger(t[1], reader_, "file type") != 0)
      reader_.fail("binary Gmsh files are not supported (save as ASCII: Mesh.Binary = 0)");
  }

  // Version 4.1 sections are read as a stream of numbers, whatever their line breaks.
  std::string_view token(const char* what) {
    while (next_ == tokens_.size()) {
      std::string_view line;
      if (!reader_.next(line)) reader_.fail(std::string("file ends in ") + what);
      tokens_ = splitWhitespace(line);
      next_ = 0;
      if (!tokens_.empty() && tokens_[0][0] == '$')
        reader_.fail(std::string("section ends early, in ") + what + " ('" + std::string(tokens_[0]) + "')");
    }
    return tokens_[next_++];
  }

  long long integer(const char* what) { return parseInteger(token(what), reader_, what); }

  // A count from a header: no more items than the file has bytes (each needs at least one), so a
  // hostile header fails here instead of in a long loop.
  long long count4(const char* what) {
    const long long n = integer(what);
    if (n < 0 || n > static_cast<long long>(textSize_) || n > std::numeric_limits<int>::max())
      reader_.fail(std::string("bad ") + what + " " + std::to_string(n) + " for a file of " +
                   std::to_string(textSize_) + " bytes");
    return n;
  }

  // numPoints numCurves numSurfaces numVolumes, then per point "tag x y z #physical physical...", per
  // other entity "tag minX minY minZ maxX maxY maxZ #physical physical... #bounding bounding...".
  void readEntities() {
    if (haveEntities_) reader_.fail("second $Entities section");
    if (haveNodes_) reader_.fail("$Entities after $Nodes");
    haveEntities_ = true;
    long long counts[4];
    for (long long& n : counts) n = count4("entity count");
    for (int dim = 0; dim < 4; ++dim)
      for (long long e = 0; e < counts[dim]; ++e) {
        const long long tag = integer("entity tag");
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) parseDouble(token("entity bounds"), reader_, "entity bounds");
        const long long physicals = count4("physical tag count");
        int physical = 0;
        for (long long k = 0; k < physicals; ++k) {
          const long long value = integer("physical tag");
          if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
            reader_.fail("physical tag " + std::to_string(value) + " out of range");
          if (k == 0) physical = static_cast<int>(value);
        }
        if (!entityPhysical_.try_emplace({dim, tag}, physical).second)
          reader_.fail("entity " + std::to_string(tag) + " of dimension " + std::to_string(dim) + " listed twice");
        if (dim == 0) continue;
        const long long bounding = count4("bounding entity count");
        for (long long k = 0; k < bounding; ++k) integer("bounding entity");
      }
  }

  int entityDimension() {
    const long long dim = integer("entity dimension");
    if (dim < 0 || dim > 3) reader_.fail("entity dimension " + std::to_string(dim) + " (0 to 3)");
    return static_cast<int>(dim);
  }

  // numEntityBlocks numNodes minNodeTag maxNodeTag; per block "entityDim entityTag parametric n", n
  // node tags, then n rows "x y z" (with u, v, w as far as the entity's dimension when parametric).
  void readNodes4() {
    if (haveNodes_) reader_.fail("second node section");
    haveNodes_ = true;
    const long long blocks = count4("node block count"), total = count4("node count");
    integer("minimum node tag");
    integer("maximum node tag");
    long long read = 0;
    std::vector<long long> tags;
    for (long long b = 0; b < blocks; ++b) {
      const int dim = entityDimension();
      integer("entity tag");
      const long long parametric = integer("parametric flag");
      if (parametric != 0 && parametric != 1) reader_.fail("parametric flag " + std::to_string(parametric));
      const long long n = count4("node count of the block");
      if (read + n > total)
        reader_.fail("node blocks hold more than the " + std::to_string(total) + " nodes of the header");
      tags.clear();
      for (long long i = 0; i < n; ++i) tags.push_back(integer("node tag"));
      for (long long tag : tags) {
        if (!nodeIndex_.try_emplace(tag, static_cast<int>(read++)).second)
          reader_.fail("node tag " + std::to_string(tag) + " used twice");
        for (int k = 0; k < 3; ++k) xyz_.push_back(parseDouble(token("node coordinates"), reader_, "node coordinate"));
        for (int k = 0; k < (parametric ? dim : 0); ++k)
          parseDouble(token("node coordinates"), reader_, "parametric coordinate");
      }
    }
    if (read != total)
      reader_.fail("node blocks hold " + std::to_string(read) + " nodes, the header says " + std::to_string(total));
  }

  // numEntityBlocks numElements minElementTag maxElementTag; per block "entityDim entityTag type n",
  // then n rows "elementTag node...".
  void readElements4() {
    if (!haveNodes_) reader_.fail("elements before nodes");
    if (haveElements_) reader_.fail("second element section");
    haveElements_ = true;
    const long long blocks = count4("element block count"), total = count4("element count");
    integer("minimum element tag");
    integer("maximum element tag");
    long long read = 0;
    for (long long b = 0; b < blocks; ++b) {
      const int dim = entityDimension();
      const long long tag = integer("entity tag");
      const long long type = integer("element type");
      const int nodes = nodesOfType(type);
      const long long n = count4("element count of the block");
      if ((read += n) > total)
        reader_.fail("element blocks hold more than the " + std::to_string(total) + " elements of the header");
      const bool kept = type == kTriangle || type == kTetrahedron;
      if (kept && dim != (type == kTriangle ? 2 : 3))
        reader_.fail(std::string(type == kTriangle ? "triangles" : "tetrahedra") + " on an entity of dimension " +
                     std::to_string(dim));
      if (kept && (tag < std::numeric_limits<int>::min() || tag > std::numeric_limits<int>::max()))
        reader_.fail("entity tag " + std::to_string(tag) + " out of range");
      int physical = 0;
      if (kept && haveEntities_) {
        const auto found = entityPhysical_.find({dim, tag});
        if (found == entityPhysical_.end())
          reader_.fail("element block on entity " + std::to_string(tag) + " of dimension " + std::to_string(dim) +
                       ", which $Entities does not list");
        physical = found->second;
      }
      Elements& out = type == kTriangle ? triangles_ : tets_;
      for (long long e = 0; e < n; ++e) {
        const long long elementTag = integer("element tag");
        if (!kept) {
          for (int k = 0; k < nodes; ++k) integer("node tag");
          continue;
        }
        out.tags.push_back(elementTag);
        out.physical.push_back(physical);
        out.elementary.push_back(static_cast<int>(tag));
        for (int k = 0; k < nodes; ++k) out.vertices.push_back(vertex(token("element nodes")));
      }
    }
    if (read != total)
      reader_.fail("element blocks hold " + std::to_string(read) + " elements, the header says " +
                   std::to_string(total));
    triangles_.sortByTag();
    tets_.sortByTag();
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
  std::size_t textSize_;
  bool version4_ = false;
  bool haveEntities_ = false;
  std::map<std::pair<int, long long>, int> entityPhysical_;  // (dimension, entity tag) -> first physical tag
  std::vector<std::string_view> tokens_;                      // current line of a 4.1 section
  std::size_t next_ = 0;                                      // next unread token of it
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

namespace {

std::string formatGmsh2(const TetMesh& mesh) {
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

void appendLine(std::string& out, std::initializer_list<long long> values) {
  bool first = true;
  for (long long value : values) {
    if (!first) out += ' ';
    detail::appendInteger(out, value);
    first = false;
  }
  out += '\n';
}

// The model entities of one dimension: one per (elementary, physical) pair of its elements.
struct Entity {
  int tag = 0, physical = 0;
  std::vector<Eigen::Index> elements;  // rows of F or T, in order
};

std::vector<Entity> entitiesOf(const Eigen::MatrixXi& elements, const AttributeSet& attributes) {
  const bool hasRegion = attributes.integer.count(kRegion) > 0;
  const Eigen::VectorXi physical = detail::referenceColumn(attributes, kLabel, elements.rows());
  const Eigen::VectorXi region = detail::referenceColumn(attributes, kRegion, elements.rows());
  std::map<std::pair<int, int>, Entity> byPair;  // (region, physical), sorted
  for (Eigen::Index e = 0; e < elements.rows(); ++e) {
    Entity& entity = byPair[{region(e), physical(e)}];
    entity.physical = physical(e);
    entity.elements.push_back(e);
  }
  // Entity tags: the elementary tags when they name the entities (positive, one physical group each);
  // without elementary tags, the physical tag (the unlabelled ones after the largest); else 1, 2, ...
  std::map<int, int> physicalsOfRegion;
  int largest = 0;
  for (const auto& [key, entity] : byPair) ++physicalsOfRegion[key.first], largest = std::max(largest, key.second);
  bool regionsName = hasRegion, physicalsName = !hasRegion;
  for (const auto& [key, entity] : byPair) {
    regionsName = regionsName && key.first > 0 && physicalsOfRegion[key.first] == 1;
    physicalsName = physicalsName && key.second >= 0;
  }
  std::vector<Entity> entities;
  int next = 0;
  for (auto& [key, entity] : byPair) {
    entity.tag = regionsName ? key.first : physicalsName ? (key.second > 0 ? key.second : largest + 1) : ++next;
    entities.push_back(std::move(entity));
  }
  return entities;
}

void appendEntityLine(std::string& out, const Entity& entity, const MatrixX3d& V, const Eigen::MatrixXi& elements) {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), max = -min;
  for (Eigen::Index e : entity.elements)
    for (Eigen::Index c = 0; c < elements.cols(); ++c) {
      min = min.cwiseMin(V.row(elements(e, c)).transpose());
      max = max.cwiseMax(V.row(elements(e, c)).transpose());
    }
  if (entity.elements.empty()) {  // the empty volume that holds the nodes of a mesh without elements: their bounds
    min = V.colwise().minCoeff().transpose();
    max = V.colwise().maxCoeff().transpose();
  }
  detail::appendInteger(out, entity.tag);
  for (double value : {min.x(), min.y(), min.z(), max.x(), max.y(), max.z()}) {
    out += ' ';
    detail::appendReal(out, value);
  }
  out += entity.physical != 0 ? " 1 " + std::to_string(entity.physical) + " 0\n" : " 0 0\n";
}

// Element tags first + 1, first + 2, ... in mesh order, whatever block an element is in.
void appendElementBlocks(std::string& out, long long first, int dim, int type, const std::vector<Entity>& entities,
                         const Eigen::MatrixXi& elements) {
  for (const Entity& entity : entities) {
    appendLine(out, {dim, entity.tag, type, static_cast<long long>(entity.elements.size())});
    for (Eigen::Index e : entity.elements) {
      detail::appendInteger(out, first + e + 1);
      for (Eigen::Index c = 0; c < elements.cols(); ++c) {
        out += ' ';
        detail::appendInteger(out, elements(e, c) + 1LL);
      }
      out += '\n';
    }
  }
}

std::string formatGmsh41(const TetMesh& mesh) {
  const std::vector<Entity> surfaces = entitiesOf(mesh.F, mesh.faceAttributes);
  const std::vector<Entity> volumes = entitiesOf(mesh.T, mesh.tetAttributes);
  // Gmsh needs every node on an entity; with no elements at all, one empty volume holds them.
  const bool nodesOnly = surfaces.empty() && volumes.empty() && mesh.V.rows() > 0;
  std::string out = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n";
  appendLine(out, {0, 0, static_cast<long long>(surfaces.size()),
                   static_cast<long long>(volumes.size()) + (nodesOnly ? 1 : 0)});
  for (const Entity& entity : surfaces) appendEntityLine(out, entity, mesh.V, mesh.F);
  for (const Entity& entity : volumes) appendEntityLine(out, entity, mesh.V, mesh.T);
  if (nodesOnly) {
    Entity empty;
    empty.tag = 1;
    appendEntityLine(out, empty, mesh.V, mesh.T);
  }
  out += "$EndEntities\n$Nodes\n";
  const long long n = mesh.V.rows();
  if (n == 0) {
    out += "0 0 0 0\n";
  } else {
    appendLine(out, {1, n, 1, n});
    const bool onVolume = !volumes.empty() || nodesOnly;
    appendLine(out, {onVolume ? 3 : 2, volumes.empty() ? (nodesOnly ? 1 : surfaces[0].tag) : volumes[0].tag, 0, n});
    for (long long i = 1; i <= n; ++i) appendLine(out, {i});
    for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (k) out += ' ';
        detail::appendReal(out, mesh.V(i, k));
      }
      out += '\n';
    }
  }
  out += "$EndNodes\n$Elements\n";
  const long long elements = mesh.F.rows() + mesh.T.rows();
  appendLine(out, {static_cast<long long>(surfaces.size() + volumes.size()), elements, elements ? 1 : 0, elements});
  appendElementBlocks(out, 0, 2, kTriangle, surfaces, mesh.F);
  appendElementBlocks(out, mesh.F.rows(), 3, kTetrahedron, volumes, mesh.T);
  out += "$EndElements\n";
  return out;
}

}  // namespace

std::string formatGmsh(const TetMesh& mesh, GmshVersion version) {
  return version == GmshVersion::k22 ? formatGmsh2(mesh) : formatGmsh41(mesh);
}

}  // namespace vesalius::io
