// The full-body reference's files read (full_body_sources.h).
#include "full_body_sources.h"
#include "shipped_data.h"

#include "vesalius/io/body_axes.h"
#include "vesalius/io/makehuman_uv.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/io/skeleton_io.h"

#include <algorithm>
#include <filesystem>

namespace vesalius::cli {

patient::FullBodySources readFullBodySources(const std::string& skin, const std::string& skeleton,
                                             const std::string& baseMesh, const std::string& model,
                                             const std::string& organs) {
  namespace fs = std::filesystem;
  const std::string base = baseMesh.empty() ? (fs::path(skeleton).parent_path() / "base.obj").string() : baseMesh;
  patient::FullBodySources s;
  s.name = "full body (" + fs::path(skin).filename().string() + ", " + fs::path(model).filename().string() + ")";
  const TriMesh baseTriMesh = io::readTriMesh(base);
  s.skin = io::readTriMesh(skin);
  s.rig = io::transformSkeleton(io::readMakeHumanSkeletonOfBody(skeleton, baseTriMesh, s.skin), io::yUpToLps(), 100.0);
  if (s.skin.UV.rows() == 0) s.skin = io::withMakeHumanUv(std::move(s.skin), baseTriMesh, base);
  s.skin.V = io::transformPoints(s.skin.V, io::yUpToLps(), 100.0);
  s.model = io::readOpenSimModel(model);
  s.model.bodies = io::transformSkeleton(s.model.bodies, io::openSimToLps(), 1000.0);
  for (Muscle& m : s.model.muscles)
    for (PathPoint& point : m.path) point.location = 1000.0 * io::openSimToLps() * point.location;
  const fs::path geometryDir = fs::path(model).parent_path() / "Geometry";
  for (const AttachedGeometry& g : s.model.geometry) {
    TriMesh mesh = io::readTriMesh((geometryDir / g.meshFile).string());
    mesh.V = io::transformPoints(mesh.V * g.scale.asDiagonal(), io::openSimToLps(), 1000.0);
    s.geometry.push_back(std::move(mesh));
    s.geometryNames.push_back(fs::path(g.meshFile).stem().string());
  }
  if (!organs.empty()) {
    s.organs = io::readReferenceAnatomy(organs);
    s.organsSource = organs;
  }
  return s;
}

std::vector<patient::OrganTemplate> readOrganTemplates(const std::string& folder) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(folder)) throw BadInput(folder, "no such template folder");
  std::vector<patient::OrganTemplate> templates;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string ext = fileExtension(e.path().string());
    if (!e.is_regular_file() || (ext != ".obj" && ext != ".stl" && ext != ".ply" && ext != ".vtp")) continue;
    templates.push_back({e.path().stem().string(), io::readTriMesh(e.path().string()), e.path().string()});
  }
  std::sort(templates.begin(), templates.end(), [](const auto& a, const auto& b) { return a.organ < b.organ; });
  return templates;
}

FullBodyFiles shippedFullBodyFiles() {
  return {shippedData("body/shapes/mh_neutral_body.obj"), shippedData("body/default.mhskel"),
          shippedData("skeleton-opensim/Rajagopal2016.osim")};
}

ReferenceAnatomy shippedFullBodyReference(bool withOrgans) {
  const FullBodyFiles files = shippedFullBodyFiles();
  const patient::FullBodySources sources = readFullBodySources(
      files.skin, files.skeleton, "", files.model, withOrgans ? shippedTemplates("reference-organs") : "");
  return patient::buildFullBodyReference(sources, files.skeleton).anatomy;
}

}  // namespace vesalius::cli
