// Reference anatomy folders (reference_anatomy_io.h).
#include "vesalius/io/reference_anatomy_io.h"

#include "vesalius/core/error.h"
#include "vesalius/core/safe_file_name.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/text_file.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <limits>
#include <type_traits>

namespace vesalius::io {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

constexpr const char* kFormat = "vesalius-reference-anatomy";

Eigen::Vector3d vector3(const Json& value, const std::string& what, const std::string& source) {
  if (!value.is_array() || value.size() != 3)
    throw BadInput(source, what + " must be an array of 3 numbers");
  Eigen::Vector3d v;
  for (int a = 0; a < 3; ++a) {
    if (!value[a].is_number()) throw BadInput(source, what + " must be an array of 3 numbers");
    v[a] = value[a].get<double>();
  }
  return v;
}

const Json& member(const Json& object, const char* key, const std::string& source, const std::string& where) {
  const auto it = object.is_object() ? object.find(key) : object.end();
  if (it == object.end()) throw BadInput(source, where + " has no \"" + key + "\"");
  return *it;
}

std::string text(const Json& object, const char* key, const std::string& source, const std::string& where) {
  const Json& value = member(object, key, source, where);
  if (!value.is_string()) throw BadInput(source, where + ": \"" + key + "\" must be a string");
  return value.get<std::string>();
}

// An optional member of the type asked for, or `fallback` when it is absent; a member of another type is
// BadInput (nlohmann's value() would throw its own type_error, which names no file).
template <class T>
T optionalMember(const Json& object, const char* key, T fallback, const std::string& source, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end()) return fallback;
  if constexpr (std::is_same_v<T, bool>) {
    if (!it->is_boolean()) throw BadInput(source, where + ": \"" + key + "\" must be true or false");
  } else {
    if (!it->is_string()) throw BadInput(source, where + ": \"" + key + "\" must be a string");
  }
  return it->template get<T>();
}

// An array member; BadInput for anything else (nlohmann iterates a number or string as one element).
const Json& arrayMember(const Json& object, const char* key, const std::string& source, const std::string& where) {
  const Json& value = member(object, key, source, where);
  if (!value.is_array()) throw BadInput(source, where + ": \"" + key + "\" must be an array");
  return value;
}

// A mesh named in reference.json (`source`): a path relative to the folder that stays inside it, so that a
// file handed to us never makes us read elsewhere.
TriMesh readMesh(const fs::path& folder, const std::string& file, const std::string& source) {
  const fs::path relative = fs::path(file).lexically_normal();
  if (file.empty() || relative.is_absolute() || relative.has_root_name() || *relative.begin() == "..")
    throw BadInput(source, "mesh file '" + file + "' lies outside the reference folder");
  return readTriMesh((folder / relative).string());
}

Json toJson(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

}  // namespace

std::string tissueFile(const std::string& name) { return "tissues/" + safeFileName(name) + ".obj"; }

ReferenceAnatomy readReferenceAnatomy(const std::string& folder) {
  const fs::path root(folder);
  const std::string source = (root / "reference.json").string();
  Json doc;
  try {
    doc = Json::parse(readTextFile(source));
  } catch (const Json::exception& e) {
    throw BadInput(source, std::string("invalid JSON: ") + e.what());
  }
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != kFormat)
    throw BadInput(source, std::string("not a reference anatomy (\"format\" is not \"") + kFormat + "\")");
  if (!doc.contains("version") || !doc["version"].is_number_integer() || doc["version"].get<long long>() != 1)
    throw BadInput(source, "unsupported reference anatomy version (\"version\" must be the number 1)");
  ReferenceAnatomy anatomy;
  anatomy.name = optionalMember<std::string>(doc, "name", folder, source, "the document");
  anatomy.skin = readMesh(root, text(doc, "skin", source, "the document"), source);
  if (doc.contains("skin_cut_vertices")) {
    if (!doc["skin_cut_vertices"].is_array()) throw BadInput(source, "\"skin_cut_vertices\" must be an array of vertex indices");
    for (const Json& v : doc["skin_cut_vertices"]) {
      if (!v.is_number_integer() || v < 0 || v > std::numeric_limits<int>::max())
        throw BadInput(source, "\"skin_cut_vertices\" must be an array of vertex indices");
      anatomy.skinCutVertices.push_back(v.get<int>());
    }
  }
  const Json& plane = member(doc, "sagittal_plane", source, "the document");
  anatomy.sagittal.point = vector3(member(plane, "point", source, "sagittal_plane"), "sagittal_plane.point", source);
  anatomy.sagittal.normal = vector3(member(plane, "normal", source, "sagittal_plane"), "sagittal_plane.normal", source);
  for (const Json& t : arrayMember(doc, "tissues", source, "the document")) {
    ReferenceTissue tissue;
    tissue.name = text(t, "name", source, "a tissue");
    const std::string where = "tissue '" + tissue.name + "'";
    try {
      tissue.kind = tissueKindFromName(text(t, "kind", source, where));
    } catch (const UsageError& e) {
      throw BadInput(source, where + ": " + e.what());
    }
    tissue.group = optionalMember<std::string>(t, "group", "", source, where);
    tissue.symmetric = optionalMember<bool>(t, "symmetric", false, source, where);
    tissue.mesh = readMesh(root, text(t, "file", source, where), source);
    anatomy.tissues.push_back(std::move(tissue));
  }
  if (doc.contains("points"))
    for (const Json& p : arrayMember(doc, "points", source, "the document")) {
      ReferencePoint point;
      point.name = text(p, "name", source, "a point");
      point.tissue = optionalMember<std::string>(p, "tissue", "", source, "point '" + point.name + "'");
      point.position = vector3(member(p, "position", source, "point '" + point.name + "'"), "point '" + point.name + "'", source);
      anatomy.points.push_back(std::move(point));
    }
  anatomy.sagittal.normal.normalize();
  anatomy.validate(source);
  return anatomy;
}

void writeReferenceAnatomy(const std::string& folder, const ReferenceAnatomy& anatomy, const WriteOptions& options,
                           const std::vector<std::pair<std::string, TriMesh>>& extras) {
  anatomy.validate(folder);
  // Whole or not at all (core/atomic_file.h): no planted symlink is followed, an interrupted write leaves
  // nothing, and a replaced folder is there, old or new, at every moment.
  writeFolderAtomically(folder, options, [&](const std::string& staging) {
    const fs::path temporary(staging);
    fs::create_directories(temporary / "tissues");
    Json doc;
    doc["format"] = kFormat;
    doc["version"] = 1;
    doc["name"] = anatomy.name;
    doc["coordinate_system"] = "LPS";
    doc["units"] = "mm";
    doc["skin"] = "skin.obj";
    writeTriMesh((temporary / "skin.obj").string(), anatomy.skin);
    doc["skin_cut_vertices"] = anatomy.skinCutVertices;
    doc["sagittal_plane"] = {{"point", toJson(anatomy.sagittal.point)}, {"normal", toJson(anatomy.sagittal.normal)}};
    doc["tissues"] = Json::array();
    for (const ReferenceTissue& tissue : anatomy.tissues) {
      const std::string file = tissueFile(tissue.name);
      if (fs::exists(temporary / file)) throw BadInput(folder, "two tissues share the file name " + file);
      writeTriMesh((temporary / file).string(), tissue.mesh);
      Json t = {{"name", tissue.name}, {"kind", tissueKindName(tissue.kind)}};
      if (!tissue.group.empty()) t["group"] = tissue.group;
      if (tissue.symmetric) t["symmetric"] = true;
      t["file"] = file;
      doc["tissues"].push_back(t);
    }
    doc["points"] = Json::array();
    for (const ReferencePoint& point : anatomy.points)
      doc["points"].push_back({{"name", point.name}, {"tissue", point.tissue}, {"position", toJson(point.position)}});
    for (const auto& [file, mesh] : extras) writeTriMesh((temporary / file).string(), mesh);
    try {
      writeFileBytes((temporary / "reference.json").string(), doc.dump(2) + '\n');
    } catch (const BadInput& error) {
      throw BadInput(folder, "reference.json: " + error.problem());
    }
  });
}

}  // namespace vesalius::io
