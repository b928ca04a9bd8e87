#include "pose_outputs.h"

#include "vesalius/core/error.h"
#include "vesalius/io/anatomy_rig_io.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/posing/posed_volume.h"
#include "vesalius/posing/untangle_tets.h"
#include "vesalius/rigging/rigid_bone_parts.h"
#include "vesalius/viz/surface_render.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

namespace fs = std::filesystem;

namespace vesalius::cli {

using posing::PoseQuality;

void writePose(const AnatomyRig& rig, const std::vector<TriMesh>& meshes, const std::vector<MatrixX3d>& carried,
               const Volumes& volumes, const MatrixX3d& posedTets, const std::vector<Eigen::Isometry3d>& world,
               const std::string& dir, const std::string& png) {
  // Every file is new: `dir` is in the staging folder of --out (core/atomic_file.h).
  const io::MeshWriteOptions write{};
  fs::create_directories(dir);
  TetMesh tets = rig.tets;
  tets.V = posedTets;
  io::writeTetMesh(dir + "/tets.vtu", tets, write);
  io::writeBvh(dir + "/skeleton.bvh", io::posedSkeletonMotion(rig.skeleton, world));
  std::vector<TriMesh> out = meshes;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    out[m].V = carried[m];
    io::writeTriMesh(dir + "/" + fs::path(rig.meshes[m]).filename().string(), out[m], write);
  }
  // The volumes keep their grids; their voxels inside a bone mesh move with it rigidly. A scan and its
  // label map mostly share a grid: the bones are then voxelized once for both.
  std::optional<posing::RigidParts> bones;
  std::optional<GridGeometry> bonesGrid;
  const auto onGrid = [&](const GridGeometry& grid) {
    posing::PosedVolumeOptions options;
    const bool same = bonesGrid && bonesGrid->size == grid.size && bonesGrid->origin == grid.origin &&
                      bonesGrid->spacing == grid.spacing && bonesGrid->direction == grid.direction;
    if (!same) {
      bones = rigging::rigidBoneParts(rig, meshes, carried, world, grid, grid);
      bonesGrid = grid;
    }
    options.rigid = &*bones;
    return options;
  };
  if (volumes.scan)
    io::writeScan(dir + "/" + volumes.scanName,
                  posing::poseImage(rig.tets.V, rig.tets.T, posedTets, *volumes.scan, onGrid(volumes.scan->geometry)));
  if (volumes.labels)
    io::writeLabelMap(dir + "/" + volumes.labelsName,
                      posing::poseLabels(rig.tets.V, rig.tets.T, posedTets, *volumes.labels,
                                         onGrid(volumes.labels->labels.geometry)));
  if (!png.empty()) {
    // The skin translucent over the other meshes, as the viewer of the issue shows them.
    std::vector<viz::SurfaceLayer> layers;
    for (std::size_t m = 0; m < out.size(); ++m) {
      const bool isSkin = fs::path(rig.meshes[m]).stem() == "skin";
      layers.push_back({&out[m], isSkin ? viz::Rgb{{230, 190, 160}} : viz::Rgb{{235, 235, 220}}, isSkin && out.size() > 1 ? 0.35 : 1.0});
    }
    viz::writeSurfacesPng(layers, png, viz::SurfaceRenderOptions{800, 800, {{24, 24, 28}}, {}});
  }
}

void writeQualityTable(const std::string& path, const std::vector<PoseSpec>& poses,
                       const std::vector<PoseQuality>& quality, const std::string& method,
                       const WriteOptions& options) {
  writeAtomically(path, options, [&](const std::string& temporary) {
    std::ofstream out(temporary);
    out << "frame\tmethod\tinverted\tmin_volume_ratio\tskin_volume_change_pct\ttissue_vertices_left_outside"
           "\tuntangled_tets\tuntangle_max_move_mm\ttet_volume_change_pct\tskinned_tet_volume_change_pct"
           "\trestore_max_move_mm\n";
    out.precision(9);
    for (std::size_t p = 0; p < poses.size(); ++p) {
      const PoseQuality& q = quality[p];
      out << (poses[p].frame < 0 ? "-" : std::to_string(poses[p].frame)) << '\t' << method << '\t' << q.inverted
          << '\t' << q.minVolumeRatio << '\t' << q.skinVolumeChangePct << '\t' << q.leftOutside << '\t'
          << q.untangle.badBefore << '\t' << q.untangle.maxMove << '\t' << q.tetVolumeChangePct << '\t'
          << q.skinnedTetVolumeChangePct << '\t' << q.restore.maxMove << '\n';
    }
    out.close();  // the last buffered bytes reach the file here, so check after it
    if (!out) throw BadInput(temporary, "cannot write");
  });
}

void reportWorstQuality(const std::vector<PoseSpec>& poses, const std::vector<PoseQuality>& quality,
                        long insideAtRest, io::Report& report) {
  std::size_t inverted = 0, ratio = 0, skin = 0, left = 0, repaired = 0, move = 0, restoreMove = 0, boneMove = 0,
              gap = 0;
  long repairedTotal = 0, boneOnly = 0, unrepaired = 0, released = 0;
  for (std::size_t p = 0; p < quality.size(); ++p) {
    repairedTotal += quality[p].untangle.badBefore;
    boneOnly += quality[p].untangle.fixedBad;
    unrepaired += quality[p].untangle.badAfter;
    released += quality[p].untangle.releasedBoneVertices;
    if (quality[p].untangle.maxBoneMove > quality[boneMove].untangle.maxBoneMove) boneMove = p;
    if (quality[p].untangle.badBefore > quality[repaired].untangle.badBefore) repaired = p;
    if (quality[p].untangle.maxMove > quality[move].untangle.maxMove) move = p;
    if (quality[p].restore.maxMove > quality[restoreMove].restore.maxMove) restoreMove = p;
    if (quality[p].inverted > quality[inverted].inverted) inverted = p;
    if (quality[p].minVolumeRatio < quality[ratio].minVolumeRatio) ratio = p;
    if (std::abs(quality[p].skinVolumeChangePct) > std::abs(quality[skin].skinVolumeChangePct)) skin = p;
    if (quality[p].leftOutside > quality[left].leftOutside) left = p;
    if (quality[p].boneMeshGapMax > quality[gap].boneMeshGapMax) gap = p;
  }
  const auto frame = [&](std::size_t p) {
    return poses[p].frame < 0 ? std::string("-") : std::to_string(poses[p].frame);
  };
  report.metric("max_inverted_tets", quality[inverted].inverted);
  report.metric("min_tet_volume_ratio", quality[ratio].minVolumeRatio);
  report.metric("worst_skin_volume_change_pct", quality[skin].skinVolumeChangePct);
  report.metric("max_tissue_vertices_left_outside", quality[left].leftOutside);
  report.metric("tissue_vertices_inside_at_rest", insideAtRest);
  report.metric("max_bone_mesh_gap_mm", quality[gap].boneMeshGapMax);
  std::cout << "worst over " << poses.size() << " pose(s): " << quality[inverted].inverted
            << " inverted or flat tets (frame " << frame(inverted) << "), smallest posed/rest tet volume "
            << quality[ratio].minVolumeRatio << " (frame " << frame(ratio) << "), skin volume change "
            << quality[skin].skinVolumeChangePct << " % (frame " << frame(skin) << "), "
            << quality[left].leftOutside << " of " << insideAtRest
            << " tissue vertices inside at rest left outside (frame " << frame(left) << ")\n";
  report.metric("max_restore_move_mm", quality[restoreMove].restore.maxMove);
  std::cout << "restoring the volume moved vertices by up to " << quality[restoreMove].restore.maxMove
            << " mm (frame " << frame(restoreMove) << ")\n";
  report.metric("untangled_tets", repairedTotal);
  report.metric("max_untangled_tets", quality[repaired].untangle.badBefore);
  report.metric("max_untangle_move_mm", quality[move].untangle.maxMove);
  report.metric("untangle_unrepaired_tets", unrepaired);
  report.metric("untangle_bone_only_tets", boneOnly);
  report.metric("untangle_released_bone_vertices", released);
  report.metric("max_untangle_bone_move_mm", quality[boneMove].untangle.maxBoneMove);
  std::cout << "untangled " << repairedTotal << " tets below " << posing::UntangleOptions().minVolumeRatio
            << " of their rest volume in all, at most "
            << quality[repaired].untangle.badBefore << " in a pose (frame " << frame(repaired)
            << "); moved vertices by up to " << quality[move].untangle.maxMove << " mm (frame " << frame(move)
            << "); " << unrepaired << " still below after, of which " << boneOnly
            << " have only bone vertices (nothing to move)\n";
  if (released > 0)
    std::cout << "folds pressed between bones freed " << released << " bone vertices in all, moved by up to "
              << quality[boneMove].untangle.maxBoneMove << " mm (frame " << frame(boneMove) << ")\n";
  if (quality[gap].boneMeshGapMax > 0)
    std::cout << "bone meshes moved rigidly lie up to " << quality[gap].boneMeshGapMax
              << " mm from where the tets carry their surroundings (frame " << frame(gap) << ")\n";
}

}  // namespace vesalius::cli
