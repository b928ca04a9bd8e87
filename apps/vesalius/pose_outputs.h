// What `vesalius pose` writes (docs/cli.md): each pose's meshes, tets, skeleton, re-posed volumes and render,
// quality.tsv, and the worst of each quality measure over the poses on stdout and in the report.
#pragma once

#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/io/report.h"
#include "vesalius/posing/pose_quality.h"

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

namespace vesalius::cli {

// One pose to put the rig in: posed world transforms of its skeleton, the output folder's name (empty: --out
// itself) and the motion frame (-1 for --angles).
struct PoseSpec {
  std::vector<Eigen::Isometry3d> world;
  std::string name;
  int frame = -1;
};

// The rest-pose volumes to re-pose, read once for all poses, and the file names their posed copies take.
struct Volumes {
  std::optional<Image> scan;
  std::optional<LabelMap> labels;
  std::string scanName, labelsName;
};

// One pose into `dir` (new, inside the staging folder of --out): carried: per mesh, its #P by 3 posed
// vertices; posedTets: #V by 3; world: the posed joints. With `png` a render, the skin translucent.
void writePose(const AnatomyRig& rig, const std::vector<TriMesh>& meshes, const std::vector<MatrixX3d>& carried,
               const Volumes& volumes, const MatrixX3d& posedTets, const std::vector<Eigen::Isometry3d>& world,
               const std::string& dir, const std::string& png);

// quality.tsv: one row per pose; a frame of "-" is an --angles pose.
void writeQualityTable(const std::string& path, const std::vector<PoseSpec>& poses,
                       const std::vector<posing::PoseQuality>& quality, const std::string& method,
                       const WriteOptions& options);

// Prints the worst value of each measure over all poses (with its frame) and puts it into the report.
void reportWorstQuality(const std::vector<PoseSpec>& poses, const std::vector<posing::PoseQuality>& quality,
                        long insideAtRest, io::Report& report);

}  // namespace vesalius::cli
