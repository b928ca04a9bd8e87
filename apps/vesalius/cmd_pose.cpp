// vesalius pose: an anatomy directory (`vesalius rig`) put into the poses of a motion or of joint angles
// (seed 001 §3.4-3.5, §5): posed meshes, the posed tet mesh and skeleton, optionally posed volumes and renders.
#include "anatomy_rig.h"
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_embedding.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/text_file.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/corotational_fem.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/joint_angles.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/posed_volume.h"
#include "vesalius/posing/retarget.h"
#include "vesalius/posing/skeleton_pose.h"
#include "vesalius/viz/surface_render.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct PoseOptions {
  std::string anatomy, motion, map, frames, angles, method = "lbs", out, volume, labels, pngDir;
  int frame = 0;
  bool motionLps = false;
  CommonOptions common;
};

// The joint map: --map, else names shared with the rig's skeleton (a MakeHuman BVH pose) when at least
// half of the rig's bones are among them, else the CMU defaults.
posing::JointMap jointMap(const PoseOptions& o, const Skeleton& source, const AnatomyRig& rig) {
  if (!o.map.empty()) return posing::parseJointMap(io::readTextFile(o.map), o.map);
  posing::JointMap shared;
  for (const Joint& joint : rig.skeleton.joints)
    if (source.find(joint.name) >= 0) shared.pairs.emplace_back(joint.name, joint.name);
  return shared.pairs.size() * 2 >= rig.skeleton.joints.size() ? shared : posing::cmuToMakeHumanJointMap();
}

std::pair<int, int> frameRange(const PoseOptions& o, int count) {
  int first = o.frame, last = o.frame;
  if (!o.frames.empty() && std::sscanf(o.frames.c_str(), "%d:%d", &first, &last) != 2)
    throw UsageError("pose: --frames must be A:B (first and last frame, inclusive)");
  if (first < 0 || last < first || last >= count)
    throw UsageError("pose: frames " + std::to_string(first) + ".." + std::to_string(last) + " outside 0.." +
                     std::to_string(count - 1) + " of " + o.motion);
  return {first, last};
}

struct Posed {
  MatrixX3d tets;  // posed tet vertices
  std::vector<Eigen::Isometry3d> world;
};

Posed skinTets(const AnatomyRig& rig, const std::vector<Eigen::Isometry3d>& world, const std::string& method) {
  const std::vector<Eigen::Isometry3d> all = posing::restToPosed(rig.skeleton, world);
  std::vector<Eigen::Isometry3d> bones;
  for (int j : rig.boneJoint) bones.push_back(all[j]);
  const MatrixX3d& V = rig.tets.V;
  if (method == "lbs") return {posing::linearBlendSkinning(V, rig.weights(), bones), world};
  if (method == "dqs") return {posing::dualQuaternionSkinning(V, rig.weights(), bones), world};
  if (method == "cor") return {posing::corSkinning(V, rig.weights(), rig.centres(), bones), world};
  return {posing::corotationalFem(V, rig.tets.T, rig.boneOfVertex(), bones).V, world};
}

// The rest-pose volumes to re-pose, read once for all poses.
struct Volumes {
  std::optional<Image> scan;
  std::optional<LabelMap> labels;
};

void writePose(const PoseOptions& o, const AnatomyRig& rig, const std::vector<TriMesh>& meshes,
               const std::vector<TetEmbedding>& embeddings, const Volumes& volumes, const Posed& posed,
               const std::string& dir, const std::string& png) {
  const io::MeshWriteOptions write{o.common.writeOptions()};
  fs::create_directories(dir);
  TetMesh tets = rig.tets;
  tets.V = posed.tets;
  io::writeTetMesh(dir + "/tets.vtu", tets, write);
  io::writeBvh(dir + "/skeleton.bvh", posedSkeletonMotion(rig.skeleton, posed.world), o.common.writeOptions());
  std::vector<TriMesh> out = meshes;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    out[m].V = embeddings[m].apply(posed.tets);
    io::writeTriMesh(dir + "/" + fs::path(rig.meshes[m]).filename().string(), out[m], write);
  }
  if (volumes.scan)
    io::writeScan(dir + "/" + fs::path(o.volume).filename().string(),
                  posing::poseImage(rig.tets.V, rig.tets.T, posed.tets, *volumes.scan), o.common.writeOptions());
  if (volumes.labels)
    io::writeLabelMap(dir + "/" + fs::path(o.labels).filename().string(),
                      posing::poseLabels(rig.tets.V, rig.tets.T, posed.tets, *volumes.labels), o.common.writeOptions());
  if (!png.empty()) {
    // The skin translucent over the other meshes, as the viewer of the issue shows them.
    std::vector<viz::SurfaceLayer> layers;
    for (std::size_t m = 0; m < out.size(); ++m) {
      const bool isSkin = fs::path(rig.meshes[m]).stem() == "skin";
      layers.push_back({&out[m], isSkin ? viz::Rgb{{230, 190, 160}} : viz::Rgb{{235, 235, 220}}, isSkin && out.size() > 1 ? 0.35 : 1.0});
    }
    viz::writeSurfacesPng(layers, png, viz::SurfaceRenderOptions{800, 800, {{24, 24, 28}}, o.common.writeOptions()});
  }
}

void runPose(const PoseOptions& o) {
  if (o.method != "lbs" && o.method != "dqs" && o.method != "cor" && o.method != "fem")
    throw UsageError("pose: --method must be lbs, dqs, cor or fem");
  if (o.motion.empty() == o.angles.empty()) throw UsageError("pose: give --motion or --angles (not both)");
  if (!o.pngDir.empty() && !viz::canRenderSurfaces())
    throw UsageError("pose: --png-dir needs a display (run under xvfb-run -a)");
  io::Report report("pose");
  report.input("anatomy", o.anatomy);
  report.parameter("method", o.method);
  const AnatomyRig rig = readAnatomyRig(o.anatomy);
  std::vector<TriMesh> meshes;
  std::vector<TetEmbedding> embeddings;
  {
    auto timer = report.time("embed");
    for (const std::string& path : rig.meshes) {
      meshes.push_back(io::readTriMesh(path));
      embeddings.push_back(embedInTets(rig.tets.V, rig.tets.T, meshes.back().V));
    }
  }
  // Each pose is a list of posed world transforms of the rig's skeleton and the name of its output.
  std::vector<std::pair<std::vector<Eigen::Isometry3d>, std::string>> poses;
  if (!o.angles.empty()) {
    poses.emplace_back(posing::poseFromJointAngles(rig.skeleton, posing::parseJointAngles(o.angles)), "");
  } else {
    report.input("motion", o.motion);
    const Motion motion = io::readBvh(o.motion);
    posing::RetargetOptions retarget;
    if (!o.motionLps) retarget.sourceAxes = io::yUpToLps();
    const posing::Retargeter retargeter(motion.skeleton, rig.skeleton, jointMap(o, motion.skeleton, rig), retarget,
                                        o.map.empty() ? "default joint map" : o.map);
    const auto [first, last] = frameRange(o, motion.frameCount());
    for (int f = first; f <= last; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05d", f);
      poses.emplace_back(retargeter.pose(motion.worldPose(f)), first == last ? "" : name);
    }
  }
  Volumes volumes;
  if (!o.volume.empty()) volumes.scan = io::readScan(o.volume);
  if (!o.labels.empty()) volumes.labels = io::readLabelMap(o.labels);
  Progress progress(o.common.progressStyle());
  progress.begin("pose", o.method);
  double skinningSeconds = 0;
  for (std::size_t p = 0; p < poses.size(); ++p) {
    const auto start = std::chrono::steady_clock::now();
    const Posed posed = skinTets(rig, poses[p].first, o.method);
    skinningSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string& name = poses[p].second;
    const std::string dir = name.empty() ? o.out : o.out + "/" + name;
    const std::string png = o.pngDir.empty() ? "" : o.pngDir + "/" + (name.empty() ? "pose" : name) + ".png";
    if (!o.pngDir.empty()) fs::create_directories(o.pngDir);
    writePose(o, rig, meshes, embeddings, volumes, posed, dir, png);
    progress.update(double(p + 1) / poses.size());
  }
  progress.end();
  report.output("poses", o.out);
  report.metric("poses", poses.size());
  report.metric("skinning_seconds_per_pose", skinningSeconds / poses.size());
  std::cout << o.out << ": " << poses.size() << " pose(s) by " << o.method << ", " << meshes.size()
            << " mesh(es) each; skinning " << 1000 * skinningSeconds / poses.size() << " ms per pose\n";
  o.common.finish(report);
}

}  // namespace

void addPoseCommand(CLI::App& app) {
  auto o = std::make_shared<PoseOptions>();
  CLI::App* cmd = app.add_subcommand("pose", "Put a rigged anatomy into the poses of a motion or of joint angles");
  cmd->add_option("--anatomy", o->anatomy, "Anatomy directory written by `vesalius rig`")->required();
  cmd->add_option("--motion", o->motion, "BVH motion (CMU or MakeHuman names; see --map)");
  cmd->add_option("--frame", o->frame, "Frame of the motion to pose (0-based)")->capture_default_str();
  cmd->add_option("--frames", o->frames, "Frames A:B (inclusive), one output folder frame_NNNNN each");
  cmd->add_option("--map", o->map, "Joint map file: 'motion-joint rig-joint' per line (default: CMU names)");
  cmd->add_flag("--motion-lps", o->motionLps, "The motion is in mm LPS (a skeleton.bvh of vesalius), not +Y up");
  cmd->add_option("--angles", o->angles, "A pose from joint angles instead: 'joint=x,y,z; ...' degrees about the "
                                         "joint's rest axes (x left, y posterior, z superior)");
  cmd->add_option("--method", o->method, "Skinning: lbs, dqs, cor or fem (co-rotational FEM reference)")
      ->capture_default_str();
  cmd->add_option("--volume", o->volume, "A scan in the rig's space to re-pose (trilinear)");
  cmd->add_option("--labels", o->labels, "A label map in the rig's space to re-pose (nearest neighbour)");
  cmd->add_option("--png-dir", o->pngDir, "Write a render of each pose here (needs a display)");
  cmd->add_option("--out", o->out, "Output directory: posed meshes, tets.vtu, skeleton.bvh")->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Examples:\n  vesalius pose --anatomy body-rig --motion testdata/motion/01_01.bvh --frame 400 --method dqs "
      "--out posed\n  vesalius pose --anatomy body-rig --angles 'upperleg01.L=-30,0,0' --method dqs --out flexed\n"
      "  xvfb-run -a vesalius pose --anatomy body-rig --motion testdata/motion/01_01.bvh --frames 0:120 "
      "--method lbs --out walk --png-dir walk-png");
  cmd->callback([o] { runPose(*o); });
}

}  // namespace vesalius::cli
