// Skeletons (joint hierarchy with rest transforms), skin weights, motions, and musculoskeletal models.
//
// Transforms map a joint's local frame to its parent's (the root's parent is the world). Lengths are in
// the unit of the file they came from until a caller scales them; the readers in `io` say which.
#pragma once

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace vesalius {

struct Joint {
  std::string name;
  int parent = -1;  // index into Skeleton::joints; -1 for a root. Parents come before children.
  Eigen::Isometry3d restLocal = Eigen::Isometry3d::Identity();  // rest pose, local to parent
  // Where the bone ends, in the joint's local frame (BVH "End Site", MakeHuman tail); zero if unknown.
  Eigen::Vector3d tail = Eigen::Vector3d::Zero();
};

struct Skeleton {
  std::vector<Joint> joints;

  int find(const std::string& name) const;  // -1 if absent
  // World rest transform of every joint.
  std::vector<Eigen::Isometry3d> restWorld() const;
  // Throws BadInput naming `source` if a parent index is out of order or names repeat.
  void validate(const std::string& source) const;
};

// One rotation channel order and the channels a BVH joint animates.
enum class Channel { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

struct Motion {
  Skeleton skeleton;                              // rest offsets of the joints
  std::vector<std::vector<Channel>> channels;     // per joint, in file order
  double frameTime = 1.0 / 30.0;                  // seconds
  Eigen::MatrixXd values;                         // #frames by (total channels), degrees and file units

  int frameCount() const { return int(values.rows()); }
  // Local transform of every joint at `frame` (rest offset, then the frame's translation/rotations).
  std::vector<Eigen::Isometry3d> localPose(int frame) const;
  std::vector<Eigen::Isometry3d> worldPose(int frame) const;
};

// Linear-blend skin weights: #V by #joints, rows summing to 1 where a vertex is weighted.
using SkinWeights = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// A musculoskeletal model as OpenSim describes it: bodies (as joints), the meshes attached to them,
// and muscles as polylines of points fixed in bodies.
struct AttachedGeometry {
  int body = -1;
  std::string meshFile;  // as written in the model, relative to its Geometry folder
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};
struct PathPoint {
  std::string name;
  int body = -1;
  Eigen::Vector3d location = Eigen::Vector3d::Zero();  // in the body's frame
};
struct Muscle {
  std::string name;
  std::vector<PathPoint> path;
};
struct MusculoskeletalModel {
  std::string name;
  Skeleton bodies;  // one joint per body; restLocal from the joint's parent and child frames
  std::vector<AttachedGeometry> geometry;
  std::vector<Muscle> muscles;
};

}  // namespace vesalius
