// Placing a musculoskeletal model's bones inside a skin by one similarity transform per body (the
// full-body reference anatomy of Dicko et al. 2013, §3: the skin with bones and muscle path points inside it). The
// skin side comes from the GRAPP 2012 paper's skeleton alignment (body_frame.h: body frame and head-spine joint) and
// the skin's rig (MakeHuman's joints); each body's joint centres are mapped onto the matching skin joints:
//  - 3 or more point pairs: the least-squares similarity (Umeyama; linalg/similarity_transform.h);
//  - 2 pairs (a long bone: proximal and distal joint): scale = ratio of the joint distances; rotation =
//    the parent body's (the skin frame's for a root) followed by the smallest rotation that turns the
//    bone's axis onto the skin's; both joints then land exactly;
//  - 1 pair (toes): the parent's scale and rotation, translated so the joint lands exactly;
//  - no pair (patella: MakeHuman has no joint for it): the parent's transform.
// Bodies with `scaleFrom` (BodyCorrespondence) are refitted in a second pass with the scales of the
// first; their one- and no-pair children follow. A target may be the parent's placed joint
// (kParentPlaced) instead of a skin point: the body then meets its placed parent at that joint (a chain),
// where the parent's own fit does not land on the skin's joint (the femoral heads in the acetabula of a
// pelvis scaled by `scaleFrom`).
// Digits (DigitCorrespondence) are placed after the bodies, bone by bone: a model that keeps a hand's
// carpals, metacarpals and phalanges in one rigid body with straight fingers (Rajagopal 2016) cannot
// follow a skin whose fingers are spread and curled (MakeHuman's), so each digit bone gets a similarity of
// its own onto one skin bone (its head and tail), as a long bone onto its two joints.
// This is not the GRAPP 2012 paper's joint-by-joint refinement of a rig (its §3.2 onwards moves joints inside the
// skin); here the skin's rig is taken as given and the model's bones follow it.
//
// Model points are joint centres in the model's default pose, in LPS mm: a body's origin is the centre
// of the joint to its parent (true for Rajagopal 2016 but for the knee, whose tibia origin is 4 mm from the
// femur-side joint frame), plus named landmarks fixed in a body.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/linalg/similarity_transform.h"

#include <Eigen/Core>

#include <map>
#include <string>
#include <vector>

namespace vesalius::transfer {

// A named point fixed in a model body: `offset` in the body's frame (LPS mm, as io::transformSkeleton
// leaves the frames).
struct ModelLandmark {
  std::string name;
  std::string body;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};

// One body's point pairs: modelPoints[i] (a body name = its origin, or a landmark name) goes to
// targetPoints[i] (a name in the target map, or kParentPlaced). Both lists have the same length, 0 to many.
// scaleFrom, if not empty, names bodies whose mean scale replaces the one the pairs give (for a body
// whose target joints are not anatomically spaced, e.g. MakeHuman's hips, 221 mm apart against
// Rajagopal's 155 mm); the pairs still give its rotation, and their centroids coincide.
// The target name for "the model point as the body's parent placed it" (a joint shared with the parent):
// no skin rig names a joint so. Only for a body with a parent; the parent's placement of the same pass.
inline const std::string kParentPlaced = "@parent";

struct BodyCorrespondence {
  std::string body;
  std::vector<std::string> modelPoints;
  std::vector<std::string> targetPoints;
  std::vector<std::string> scaleFrom = {};
};

// A digit of one model body: its bones (mesh names, the file name's stem), proximal to distal, each placed
// onto one bone of the skin's rig: the bone's proximal joint on the skin bone's head, its distal joint on
// the skin bone's tail; the last bone (the tip) only along its skin bone (placeDigits). The model's joints
// are taken from the meshes (digitJoints).
struct DigitCorrespondence {
  std::string body;
  std::vector<std::string> bones;
  std::vector<std::string> skinBones;  // as many as bones
};

struct SkeletonCorrespondence {
  std::vector<ModelLandmark> landmarks;
  std::vector<BodyCorrespondence> bodies;  // bodies not listed move with their parent
  std::vector<DigitCorrespondence> digits;  // bones placed one by one instead of with their body
};

// Rajagopal 2016 (testdata/skeleton-opensim) onto MakeHuman's default.mhskel: targets are MakeHuman bone
// names (the bone's head joint), "head-spine" (body_frame.h) and, for the femurs' hip centres, the placed
// pelvis's (kParentPlaced: MakeHuman's hips are 221 mm apart, the pelvis's 158). The hands' five digits
// (metacarpal and phalanges) go onto MakeHuman's metacarpal and finger bones. The table itself is in
// docs/methods/skeleton-alignment.md with the reasons for each pair.
SkeletonCorrespondence rajagopalToMakeHuman();

// Each joint's rest position (world translation) by joint name: the target map of a rig. #joints entries.
std::map<std::string, Eigen::Vector3d> jointPositions(const Skeleton& skeleton);

// Each bone's rest head and tail (world; the tail is Joint::tail) by bone name: the skin bones of digits.
std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>> boneSegments(const Skeleton& skeleton);

struct SkeletonPlacement {
  std::vector<SimilarityTransform> bodies;  // one per model body, model order
  std::vector<double> rmsResidual;               // mm, of each body's point pairs after the fit (0 if < 2)
};

// model: the model's bodies in LPS mm (io::transformSkeleton of an OpenSim model). skinAxes: the skin's
// body frame (BodyFrame::axes()), the rotation taken for a root with fewer than 3 pairs. Throws BadInput
// naming a body, point or target that does not exist, a root with a kParentPlaced target, or a body whose
// pairs are degenerate.
SkeletonPlacement placeSkeleton(const Skeleton& model, const SkeletonCorrespondence& correspondence,
                                const std::map<std::string, Eigen::Vector3d>& targets, const Eigen::Matrix3d& skinAxes);

// Points fixed in `body` (#P by 3, in the body's frame, LPS mm: mesh vertices, path point locations) to
// their placed world positions: the model's rest pose, then the body's similarity. Throws UsageError for a
// body index out of range.
MatrixX3d placeBodyPoints(const Skeleton& model, const SkeletonPlacement& placement, int body, const MatrixX3d& local);

// The joints of a digit from its bones' meshes (#bones + 1 rows, in the meshes' space): the first bone's
// proximal end, the midpoints of each bone's distal end and the next bone's proximal end, the last bone's
// distal end. A bone's ends are the extremes of its vertices along its principal axis, on that axis (through
// the centroid), the proximal one the end nearer to `base` (for the first bone) or to the previous bone's
// centroid. Throws BadInput naming the bone for a mesh with fewer than 3 vertices.
MatrixX3d digitJoints(const std::vector<MatrixX3d>& bones, const Eigen::Vector3d& base);

// The digits of `correspondence` placed bone by bone: per bone (by mesh name) the similarity that takes its
// vertices in the model's rest pose (world, as restWorldPoints gives them) into the skin. Each is the
// two-point fit of the bone's joints (digitJoints, from the body's origin) onto its skin bone's head and
// tail, turned from the previous bone's rotation (the body's placed one for the first), so the twist about
// the digit comes from the body. The last bone of a digit of two or more (the tip, whose skin bone ends at
// the skin, past the bone) has the mean scale of the others, its proximal joint on its skin bone's head and
// its axis along that bone. localMeshes: each named bone's vertices in its body's frame. Throws BadInput
// naming a body, bone or skin bone that does not exist, or a bone whose joints coincide.
std::map<std::string, SimilarityTransform> placeDigits(
    const Skeleton& model, const SkeletonPlacement& placement, const std::vector<DigitCorrespondence>& digits,
    const std::map<std::string, MatrixX3d>& localMeshes,
    const std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>>& skinBones);

// Points fixed in `body` (#P by 3, in the body's frame) in the model's rest pose (world, LPS mm). Throws
// UsageError for a body index out of range.
MatrixX3d restWorldPoints(const Skeleton& model, int body, const MatrixX3d& local);

// Every muscle's path (#points by 3, world LPS mm) with each point placed with its body. Locations must
// be in LPS mm (converted like the model). Throws UsageError for a point fixed to ground.
std::vector<MatrixX3d> placeMusclePaths(const Skeleton& model, const SkeletonPlacement& placement,
                                        const std::vector<Muscle>& muscles);

}  // namespace vesalius::transfer
