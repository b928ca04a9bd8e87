// vesalius pose: an anatomy directory (`vesalius rig`) put into the poses of a motion or of joint angles
// (Sujar et al. 2018, §3.4-3.5, §5): posed meshes, the posed tet mesh and skeleton, optionally posed volumes and renders,
// and the quality of every pose (issue 6): inverted tets, posed/rest tet volumes, the skin's volume change and
// the tissue vertices that leave their tet. The skinned tets first get their rest volumes back
// (posing/volume_restoration.h) unless --no-restore-volume, then the tets skinning inverts or flattens are
// repaired (posing/untangle_tets.h) unless --no-untangle.
#include "command_runner.h"
#include "common.h"
#include "label_map_input.h"
#include "pose_outputs.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/posing/joint_angles.h"
#include "vesalius/posing/pose_quality.h"
#include "vesalius/rigging/rig_session.h"
#include "vesalius/viz/surface_render.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct PoseOptions {
  std::string anatomy, motion, map, frames, angles, method = "lbs", out, volume, labels, grid, pngDir;
  int frame = 0, every = 1;
  bool everyGiven = false, qualityOnly = false, motionLps = false, noUntangle = false, noRestore = false;
  CommonOptions common;
};

std::pair<int, int> frameRange(const PoseOptions& o, int count) {
  int first = o.frame, last = o.frame;
  if (!o.frames.empty() && std::sscanf(o.frames.c_str(), "%d:%d", &first, &last) != 2)
    throw UsageError("pose: --frames must be A:B (first and last frame, inclusive)");
  if (first < 0 || last < first || last >= count)
    throw UsageError("pose: frames " + std::to_string(first) + ".." + std::to_string(last) + " outside 0.." +
                     std::to_string(count - 1) + " of " + o.motion);
  return {first, last};
}

// The poses asked for: one of --angles, or frames A, A+K, ... <= B of --motion retargeted to the rig.
std::vector<PoseSpec> readPoses(const PoseOptions& o, const AnatomyRig& rig, io::Report& report) {
  if (!o.angles.empty())
    return {{posing::poseFromJointAngles(rig.skeleton, posing::parseJointAngles(o.angles)), "", -1}};
  report.input("motion", o.motion);
  const rigging::RetargetedMotion motion(io::readBvh(o.motion, std::cerr), o.map, o.motionLps, rig.skeleton);
  const auto [first, last] = frameRange(o, motion.frameCount());
  std::vector<PoseSpec> poses;
  for (int f = first; f <= last; f += o.every) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d", f);
    poses.push_back({motion.pose(f), first == last ? "" : name, f});
  }
  return poses;
}

void checkOptions(const PoseOptions& o) {
  if (!posing::isSkinningMethod(o.method))
    throw UsageError("pose: --method must be lbs, dqs, cor or fem");
  if (o.motion.empty() == o.angles.empty()) throw UsageError("pose: give --motion or --angles (not both)");
  if (o.every < 1) throw UsageError("pose: --every must be 1 or more");
  if (o.everyGiven && o.frames.empty()) throw UsageError("pose: --every needs --frames A:B");
  if (o.qualityOnly && (!o.pngDir.empty() || !o.volume.empty() || !o.labels.empty()))
    throw UsageError("pose: --quality-only writes no poses, so no --png-dir, --volume or --labels");
  if (!o.pngDir.empty() && !viz::canRenderSurfaces())
    throw UsageError("pose: --png-dir needs a display (run under xvfb-run -a)");
  if (!o.volume.empty() && !o.labels.empty() && fs::path(o.volume).filename() == fs::path(o.labels).filename())
    throw UsageError("pose: --volume and --labels have the same file name, which their posed copies keep");
  // The folders are written whole at the end (core/atomic_file.h); their paths are checked before the work.
  checkOutputFolder(o.out, o.common.writeOptions());
  if (!o.pngDir.empty()) checkOutputFolder(o.pngDir, o.common.writeOptions());
}

void runPose(const PoseOptions& o, CommandRun& run) {
  checkOptions(o);
  run.report.input("anatomy", o.anatomy);
  run.report.parameter("method", o.method);
  // The volumes before the rig's embedding, so that a bad one is refused before the work.
  Volumes volumes;
  if (!o.volume.empty()) volumes.scan = io::readScan(o.volume);
  if (!o.labels.empty()) volumes.labels = readLabelsOption(o.labels, "", o.grid, run.report);
  volumes.scanName = fs::path(o.volume).filename().string();
  volumes.labelsName = fs::path(o.labels).filename().string();
  // An RT Structure Set found by its content (a PACS export named RS000001 or x.dcm) is written back under
  // a name that says what it is, which writeLabelMap goes by.
  if (!o.grid.empty() && !io::isDicomRtStructPath(volumes.labelsName)) {
    const fs::path name(volumes.labelsName);
    volumes.labelsName = (io::isDicomSegPath(name) ? name.stem().string() : volumes.labelsName) + ".rtstruct.dcm";
  }
  const posing::RigPoser session = [&] {
    auto timer = run.report.time("embed");
    return rigging::readRigPoser(o.anatomy, !o.noUntangle, !o.noRestore);
  }();
  const AnatomyRig& rig = session.rig();
  const std::vector<TriMesh>& meshes = session.meshes();
  const std::vector<PoseSpec> poses = readPoses(o, rig, run.report);
  const posing::QualityMeter meter(rig, meshes, session.embeddings());
  std::vector<posing::PoseQuality> quality;
  double skinningSeconds = 0, restoreSeconds = 0, untangleSeconds = 0;  // skinning includes both
  // Every pose into the staging folders `out` and `pngDir`, then quality.tsv.
  const auto poseAll = [&](const std::string& out, const std::string& pngDir) {
    run.progress.begin("pose", o.method);
    for (std::size_t p = 0; p < poses.size(); ++p) {
      const auto start = std::chrono::steady_clock::now();
      MatrixX3d tets;
      const posing::RigPoser::Repairs repairs = session.skinTets(poses[p].world, o.method, tets);
      skinningSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::vector<MatrixX3d> carried;
      session.carry(tets, poses[p].world, carried);
      quality.push_back(meter(tets, carried));
      quality.back().restore = repairs.restore;
      quality.back().untangle = repairs.untangle;
      quality.back().skinnedTetVolumeChangePct =
          o.noRestore ? std::numeric_limits<double>::quiet_NaN() : 100 * repairs.restore.volumeChangeBefore;
      restoreSeconds += repairs.restore.seconds;
      untangleSeconds += repairs.untangle.seconds;
      if (!o.qualityOnly) {
        const std::string& name = poses[p].name;
        const std::string dir = name.empty() ? out : out + "/" + name;
        const std::string png = pngDir.empty() ? "" : pngDir + "/" + (name.empty() ? "pose" : name) + ".png";
        writePose(rig, meshes, carried, volumes, tets, poses[p].world, dir, png);
      }
      run.progress.update(double(p + 1) / poses.size());
    }
    run.progress.end();
    writeQualityTable(out + "/quality.tsv", poses, quality, o.method, {});
  };
  // Both folders whole or not at all: the renders' folder is moved into place just before --out.
  writeFolderAtomically(o.out, o.common.writeOptions(), [&](const std::string& out) {
    if (o.pngDir.empty()) return poseAll(out, "");
    writeFolderAtomically(o.pngDir, o.common.writeOptions(), [&](const std::string& pngDir) { poseAll(out, pngDir); });
  });
  run.report.output("poses", o.out);
  run.report.metric("poses", poses.size());
  const double skinOnly = skinningSeconds - restoreSeconds - untangleSeconds;
  run.report.metric("skinning_seconds_per_pose", skinOnly / poses.size());
  run.report.metric("restore_seconds_per_pose", restoreSeconds / poses.size());
  run.report.metric("untangle_seconds_per_pose", untangleSeconds / poses.size());
  std::cout << o.out << ": " << poses.size() << " pose(s) by " << o.method << ", " << meshes.size()
            << " mesh(es) each; skinning " << 1000 * skinOnly / poses.size() << " ms, restoring the volume "
            << 1000 * restoreSeconds / poses.size() << " ms and untangling " << 1000 * untangleSeconds / poses.size()
            << " ms per pose\n";
  reportWorstQuality(poses, quality, meter.insideAtRest(), run.report);
}

}  // namespace

void addPoseCommand(CLI::App& app) {
  auto o = std::make_shared<PoseOptions>();
  CLI::App* cmd = app.add_subcommand("pose", "Put a rigged anatomy into the poses of a motion or of joint angles");
  cmd->add_option("--anatomy", o->anatomy, "Anatomy directory written by `vesalius rig`")->required();
  cmd->add_option("--motion", o->motion, "BVH motion (CMU or MakeHuman names; see --map)");
  cmd->add_option("--frame", o->frame, "Frame of the motion to pose (0-based)")->capture_default_str();
  cmd->add_option("--frames", o->frames, "Frames A:B (inclusive), one output folder frame_NNNNN each");
  CLI::Option* every =
      cmd->add_option("--every", o->every, "With --frames: every K-th frame from A")->capture_default_str();
  cmd->add_option("--map", o->map, "Joint map file: 'motion-joint rig-joint' per line (default: CMU names)");
  cmd->add_flag("--motion-lps", o->motionLps, "The motion is in mm LPS (a skeleton.bvh of vesalius), not +Y up");
  cmd->add_option("--angles", o->angles, "A pose from joint angles instead: 'joint=x,y,z; ...' degrees about the "
                                         "joint's rest axes (x left, y posterior, z superior)");
  cmd->add_option("--method", o->method, "Skinning: lbs, dqs, cor or fem (co-rotational FEM reference)")
      ->capture_default_str();
  cmd->add_option("--volume", o->volume, "A scan in the rig's space to re-pose (trilinear)");
  addLabelsOption(*cmd, o->labels, o->grid,
                  "A label map in the rig's space to re-pose (nearest neighbour); an RT Structure Set with --grid");
  cmd->add_option("--png-dir", o->pngDir, "Write a render of each pose here (needs a display)");
  cmd->add_flag("--no-restore-volume", o->noRestore,
                "Keep the volume skinning loses or gains: no smooth displacement giving the tets their rest volumes "
                "back (the paper's bare skinning, with --no-untangle)");
  cmd->add_flag("--no-untangle", o->noUntangle,
                "Keep the skinned tets as they are: no repair of the tets skinning inverts or flattens");
  cmd->add_flag("--quality-only", o->qualityOnly, "Write only quality.tsv (inverted tets, volume changes), no poses");
  cmd->add_option("--out", o->out, "Output directory: posed meshes, tets.vtu, skeleton.bvh; quality.tsv")->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Examples:\n  vesalius pose --anatomy body-rig --motion testdata/motion/01_01.bvh --frame 400 --method dqs "
      "--out posed\n  vesalius pose --anatomy body-rig --angles 'upperleg01.L=-30,0,0' --method dqs --out flexed\n"
      "  xvfb-run -a vesalius pose --anatomy body-rig --motion testdata/motion/01_01.bvh --frames 0:120 "
      "--method lbs --out walk --png-dir walk-png\n"
      "  vesalius pose --anatomy body-rig --motion testdata/motion/01_01.bvh --frames 0:2751 --every 25 "
      "--method cor --quality-only --out cor-quality");
  cmd->callback([o, every] {
    o->everyGiven = every->count() > 0;
    runCommand("pose", o->common, [&](CommandRun& run) { runPose(*o, run); });
  });
}

}  // namespace vesalius::cli
