// The full-body reference's files read (full_body_sources.h).
#include "full_body_sources.h"

#include "vesalius/io/body_axes.h"
#include "vesalius/io/makehuman_uv.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/skeleton_io.h"

#include <filesystem>

namespace vesalius::cli {

patient::FullBodySources readFullBodySources(const std::string& skin, const std::string& skeleton,
                                             const std::string& baseMesh, const std::string& model) {
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
  return s;
}

}  // namespace vesalius::cli
