// A skeleton from bones segmented in a scan (Sujar et al. 2018, §3.1, rigging from labelled bone regions): joint
// centres and local frames computed from the labelled voxels of the pelvis, femurs and lumbar spine (the
// labels TotalSegmentator gives a CT, as in testdata/ct-abdomen-pelvis).
//
// Sujar et al. 2018 designs the computation bone by bone (its supplementary Matlab code, which we do not have).
// Ours, all points being voxel centres in mm (LPS); a label's boundary voxels are those with a 6-neighbour
// of another label or outside the grid:
// - Hip joint centres: the femoral head is the femur's boundary voxels within `acetabulumDistance` of the
//   hip bone's (the part of the head facing the acetabulum); its least-squares sphere (sphere_fit.h) gives
//   the centre. Boundary voxel centres lie half a voxel inside the surface, so the radius comes out about
//   half a voxel short; the centre does not move.
// - Pelvis (the root): the two hip bones and the sacrum are one rigid bone (the sacroiliac joints and the
//   symphysis barely move), at the midpoint of the hip centres. x: from the right hip centre to the left;
//   z: towards the L5/S1 disc centre (the sacrum's centroid without a spine), made orthogonal to x, so
//   that it leans back by the pelvic tilt; y = z × x (posterior).
// - Femurs: at the hip centres; z: the principal axis of the femur's voxels, signed towards the hip
//   centre (proximal); x: the pelvis's x made orthogonal to z. Hip flexion is then a negative angle about
//   x (joint_angles.h). A femur cut short by the scan gives a principal axis between shaft and neck.
// - Lumbar spine: vertebrae chained upward from the sacrum while their labels are present, each joint at
//   the centre of the disc below it: the mean of both neighbours' boundary voxels within `discDistance` of
//   the other (their end plates; facet joints within reach pull the mean back by a few mm). z: from the
//   disc below to the disc above (for the top vertebra: to its own centroid), x as for the femurs.
// Tails (bone ends, core/skeleton.h): the femur's far end along its axis, a vertebra's disc above (the top
// one's centroid), none for the pelvis.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/posing/sphere_fit.h"

#include <string>
#include <vector>

namespace vesalius::posing {

struct SkeletonFromBonesOptions {
  // Label names (case-insensitive, as the map's table has them); these are TotalSegmentator's.
  std::string hipLeft = "hip_left", hipRight = "hip_right", sacrum = "sacrum";
  std::string femurLeft = "femur_left", femurRight = "femur_right";
  // Upward from the sacrum; the chain stops at the first label absent from the map or without voxels.
  std::vector<std::string> spine{"vertebrae_L5", "vertebrae_L4", "vertebrae_L3", "vertebrae_L2", "vertebrae_L1"};
  double acetabulumDistance = 6.0;  // mm: femoral head voxels this close to the hip bone
  double discDistance = 12.0;       // mm: end plate voxels this close to the neighbouring vertebra
};

struct BoneSkeleton {
  // Joints: "pelvis" (root), "femur_left", "femur_right", then the vertebrae by label name, upward; rest
  // frames rotated as above (mm, LPS).
  Skeleton skeleton;
  std::vector<std::vector<Label>> labels;  // per joint, the labels of its bone (pelvis: hips and sacrum)
  SphereFit femoralHeadLeft, femoralHeadRight;
  long femoralHeadPointsLeft = 0, femoralHeadPointsRight = 0;  // voxels each sphere was fitted to
};

// Throws BadInput naming `source` if a hip bone, femur or the sacrum has no label or no voxels, if a
// femoral head has fewer than 10 voxels within acetabulumDistance of its hip bone, or if two neighbours
// of the spine have no voxels within discDistance of each other.
BoneSkeleton skeletonFromBones(const LabelMap& labels, const SkeletonFromBonesOptions& options = {},
                               const std::string& source = "labels");

}  // namespace vesalius::posing
