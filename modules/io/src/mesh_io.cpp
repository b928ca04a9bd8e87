// Mesh files by extension, and mesh summaries (mesh_io.h).
#include "vesalius/io/mesh_io.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/io/gltf.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/text_file.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <utility>

namespace vesalius::io {

namespace {

namespace fs = std::filesystem;

constexpr const char* kSurfaceExtensions = "(.stl, .obj, .ply, .vtk, .vtp, .glb)";
constexpr const char* kTetExtensions = "(.vtu, .vtk, .node, .ele, .mesh, .msh)";

// The dataset type of a VTK legacy file ("polydata", "unstructured_grid", ...), from its header: a
// version line, a title line, ASCII or BINARY, then "DATASET <type>".
std::string legacyDatasetType(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw BadInput(path, "cannot open");
  std::string line;
  for (int i = 0; i < 4 && std::getline(in, line); ++i) {
    if (i == 0 && line.rfind("# vtk DataFile", 0) != 0) break;
    std::istringstream tokens(line);
    std::string keyword, type;
    tokens >> keyword >> type;
    std::transform(keyword.begin(), keyword.end(), keyword.begin(), [](unsigned char c) { return std::toupper(c); });
    std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return std::tolower(c); });
    if (i == 3 && keyword == "DATASET") return type;
  }
  throw BadInput(path, "not a VTK legacy file (expected '# vtk DataFile' and a DATASET line)");
}

void requireDataset(const std::string& path, const std::string& wanted, const char* what) {
  const std::string type = legacyDatasetType(path);
  if (type != wanted) throw BadInput(path, "holds VTK " + type + ", not " + what);
}

// "liver.node" -> "liver".
std::string withoutExtension(const std::string& path) {
  return path.substr(0, path.size() - fileExtension(path).size());
}

void writeTextAtomically(const std::string& path, const WriteOptions& options, const std::string& content) {
  writeAtomically(path, options, [&](const std::string& temporary) { writeFileBytes(temporary, content); });
}

TetMesh readTetGen(const std::string& path) {
  const std::string base = withoutExtension(path);
  const std::string face = fs::exists(base + ".face") ? readTextFile(base + ".face") : std::string();
  return parseTetGen(readTextFile(base + ".node"), readTextFile(base + ".ele"), face, base);
}

// All three files or none: existing ones are checked before any is written, and a .face left from an
// earlier mesh is removed (with force) so it cannot be read back with this one.
void writeTetGen(const TetMesh& mesh, const std::string& path, const WriteOptions& options) {
  const std::string base = withoutExtension(path);
  const TetGenFiles files = formatTetGen(mesh);
  const std::pair<std::string, const std::string*> outputs[] = {
      {base + ".node", &files.node}, {base + ".ele", &files.ele}, {base + ".face", &files.face}};
  if (!options.force)
    for (const auto& [target, content] : outputs)
      if (fs::exists(target)) throw UsageError(target + ": exists; pass --force to replace it");
  for (const auto& [target, content] : outputs) {
    if (!content->empty())
      writeTextAtomically(target, options, *content);
    else
      fs::remove(target);
  }
}

std::vector<std::string> attributeNames(const AttributeSet& attributes) {
  std::vector<std::string> names;
  for (const auto& entry : attributes.integer) names.push_back(entry.first);
  for (const auto& entry : attributes.real) names.push_back(entry.first);
  std::sort(names.begin(), names.end());
  return names;
}


std::string boundsText(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  std::ostringstream out;
  out << "bounds (mm): ";
  for (int k = 0; k < 3; ++k) out << (k ? " x " : "") << "[" << min(k) << ", " << max(k) << "]";
  return out.str();
}

std::string namesText(const char* what, const std::vector<std::string>& names) {
  std::string out = std::string(what) + " attributes: ";
  for (std::size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out + (names.empty() ? "none" : "");
}

}  // namespace

std::optional<MeshKind> meshFileKind(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".vtp" || ext == ".glb") return MeshKind::kSurface;
  if (ext == ".vtu" || ext == ".node" || ext == ".ele" || ext == ".mesh" || ext == ".msh")
    return MeshKind::kTetrahedral;
  if (ext != ".vtk") return std::nullopt;
  const std::string type = legacyDatasetType(path);
  if (type == "polydata") return MeshKind::kSurface;
  if (type == "unstructured_grid") return MeshKind::kTetrahedral;
  throw BadInput(path, "holds VTK " + type + ", neither polydata (a surface) nor an unstructured grid (a tet mesh)");
}

namespace {

TriMesh readTriMeshAsStored(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".stl") return parseStl(readBinaryFile(path), path);
  if (ext == ".obj") return parseObj(readTextFile(path), path);
  if (ext == ".vtk") requireDataset(path, "polydata", "polydata (a surface)");
  if (ext == ".ply" || ext == ".vtk" || ext == ".vtp") return readVtkSurface(path);
  if (ext == ".glb") {
    // A model of several nodes is read as one surface holding all of them (what `info` describes).
    const std::vector<GltfMesh> nodes = readGlb(path);
    TriMesh all;
    Eigen::Index vertices = 0, triangles = 0;
    for (const GltfMesh& node : nodes) vertices += node.mesh.V.rows(), triangles += node.mesh.F.rows();
    all.V.resize(vertices, 3);
    all.F.resize(triangles, 3);
    vertices = triangles = 0;
    for (const GltfMesh& node : nodes) {
      all.V.middleRows(vertices, node.mesh.V.rows()) = node.mesh.V;
      all.F.middleRows(triangles, node.mesh.F.rows()) = node.mesh.F.array() + int(vertices);
      vertices += node.mesh.V.rows(), triangles += node.mesh.F.rows();
    }
    return all;
  }
  throw BadInput(path, "not a surface mesh extension " + std::string(kSurfaceExtensions));
}

}  // namespace

// A surface stored with per-face copies of its corners is read connected (STL's reader merges always, as its
// corners are all separate). Only such surfaces are merged: an open surface whose boundary the merge
// shortens. A closed surface, or one whose vertex numbers carry meaning (a reference's skin, MakeHuman's
// vertex i), keeps every vertex even where two happen to lie at the same point.
TriMesh readTriMesh(const std::string& path) {
  TriMesh stored = readTriMeshAsStored(path);
  const long boundary = countEdges(stored.F).boundary;
  if (boundary == 0) return stored;
  TriMesh merged = mergeCoincidentVertices(stored);
  return countEdges(merged.F).boundary < boundary ? merged : stored;
}

TetMesh readTetMesh(const std::string& path) {
  const std::string ext = fileExtension(path);
  if (ext == ".node" || ext == ".ele") return readTetGen(path);
  if (ext == ".mesh") return parseMedit(readTextFile(path), path);
  if (ext == ".msh") return parseGmsh(readTextFile(path), path);
  if (ext == ".vtk") requireDataset(path, "unstructured_grid", "an unstructured grid (a tet mesh)");
  if (ext == ".vtu" || ext == ".vtk") return readVtkTetMesh(path);
  throw BadInput(path, "not a tet mesh extension " + std::string(kTetExtensions));
}

void writeTriMesh(const std::string& path, const TriMesh& mesh, const MeshWriteOptions& options) {
  mesh.validate("mesh to write to " + path);
  const std::string ext = fileExtension(path);
  if (ext == ".stl")
    writeTextAtomically(path, options, options.binary ? formatStlBinary(mesh, path) : formatStlAscii(mesh));
  else if (ext == ".obj")
    writeTextAtomically(path, options, formatObj(mesh));
  else if (ext == ".ply" || ext == ".vtk" || ext == ".vtp")
    writeAtomically(path, options,
                    [&](const std::string& temporary) { writeVtkSurface(mesh, temporary, options.binary); });
  else if (ext == ".glb")
    writeGlb(path, {{fs::path(path).stem().string(), &mesh, {0.8, 0.8, 0.8, 1.0}}}, options);
  else
    throw UsageError(path + ": not a surface mesh extension " + kSurfaceExtensions);
}

void writeTetMesh(const std::string& path, const TetMesh& mesh, const MeshWriteOptions& options) {
  mesh.validate("mesh to write to " + path);
  const std::string ext = fileExtension(path);
  if (ext == ".node" || ext == ".ele")
    writeTetGen(mesh, path, options);
  else if (ext == ".mesh")
    writeTextAtomically(path, options, formatMedit(mesh));
  else if (ext == ".msh")
    writeTextAtomically(path, options, formatGmsh(mesh));
  else if (ext == ".vtu" || ext == ".vtk")
    writeAtomically(path, options,
                    [&](const std::string& temporary) { writeVtkTetMesh(mesh, temporary, options.binary); });
  else
    throw UsageError(path + ": not a tet mesh extension " + kTetExtensions);
}

TriMeshSummary summarize(const TriMesh& mesh) {
  TriMeshSummary summary;
  summary.vertices = mesh.V.rows();
  summary.triangles = mesh.F.rows();
  if (mesh.V.rows() > 0) {
    summary.min = mesh.V.colwise().minCoeff();
    summary.max = mesh.V.colwise().maxCoeff();
  }
  const EdgeCounts edges = countEdges(mesh.F);
  summary.boundaryEdges = edges.boundary;
  summary.nonManifoldEdges = edges.nonManifold;
  summary.components = triangleComponents(mesh.V.rows(), mesh.F);
  summary.closed = mesh.F.rows() > 0 && edges.boundary == 0 && edges.nonManifold == 0;
  if (summary.closed) summary.volume = enclosedVolume(mesh.V, mesh.F);
  summary.selfIntersections = long(selfIntersections(mesh.V, mesh.F).size());
  summary.hasUv = mesh.FUV.rows() > 0;
  summary.vertexAttributes = attributeNames(mesh.vertexAttributes);
  summary.faceAttributes = attributeNames(mesh.faceAttributes);
  return summary;
}

TetMeshSummary summarize(const TetMesh& mesh) {
  TetMeshSummary summary;
  summary.vertices = mesh.V.rows();
  summary.tets = mesh.T.rows();
  summary.triangles = mesh.F.rows();
  if (mesh.V.rows() > 0) {
    summary.min = mesh.V.colwise().minCoeff();
    summary.max = mesh.V.colwise().maxCoeff();
  }
  const Eigen::VectorXd volumes = tetVolumes(mesh.V, mesh.T);
  if (volumes.size() > 0) {
    summary.totalVolume = volumes.sum();
    summary.minVolume = volumes.minCoeff();
    summary.maxVolume = volumes.maxCoeff();
    summary.inverted = static_cast<long>((volumes.array() < 0).count());
  }
  const auto labels = mesh.tetAttributes.integer.find(kLabel);
  if (labels != mesh.tetAttributes.integer.end())
    for (Eigen::Index t = 0; t < labels->second.size(); ++t) {
      ++summary.tetsPerLabel[labels->second(t)];
      summary.volumePerLabel[labels->second(t)] += volumes(t);
    }
  summary.vertexAttributes = attributeNames(mesh.vertexAttributes);
  summary.tetAttributes = attributeNames(mesh.tetAttributes);
  summary.faceAttributes = attributeNames(mesh.faceAttributes);
  return summary;
}

std::string describe(const TriMeshSummary& s) {
  std::ostringstream out;
  out << std::setprecision(6) << "surface mesh: " << s.vertices << " vertices, " << s.triangles << " triangles, "
      << s.components << " connected component(s), texture coordinates: " << (s.hasUv ? "yes" : "no") << "\n"
      << boundsText(s.min, s.max) << "\n"
      << "edges: " << s.boundaryEdges << " boundary, " << s.nonManifoldEdges << " non-manifold ("
      << (s.closed ? "closed 2-manifold" : "not closed") << ")\n";
  out << "self-intersections: " << s.selfIntersections << " pairs of crossing triangles\n";
  if (s.volume) out << "enclosed volume: " << *s.volume << " mm^3\n";
  out << namesText("vertex", s.vertexAttributes) << "\n" << namesText("face", s.faceAttributes) << "\n";
  return out.str();
}

std::string describe(const TetMeshSummary& s) {
  std::ostringstream out;
  out << std::setprecision(6) << "tet mesh: " << s.vertices << " vertices, " << s.tets << " tetrahedra, "
      << s.triangles << " boundary triangles\n"
      << boundsText(s.min, s.max) << "\n"
      << "volume: " << s.totalVolume << " mm^3 total, tets from " << s.minVolume << " to " << s.maxVolume
      << " mm^3, " << s.inverted << " inverted\n";
  if (!s.tetsPerLabel.empty()) {
    out << "labels (tets, mm^3):";
    for (const auto& [label, count] : s.tetsPerLabel)
      out << " " << label << " (" << count << ", " << s.volumePerLabel.at(label) << ")";
    out << "\n";
  }
  out << namesText("vertex", s.vertexAttributes) << "\n"
      << namesText("tet", s.tetAttributes) << "\n"
      << namesText("face", s.faceAttributes) << "\n";
  return out.str();
}

}  // namespace vesalius::io
