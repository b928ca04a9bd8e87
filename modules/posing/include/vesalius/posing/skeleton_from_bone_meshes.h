// A skeleton of the whole body from bone meshes placed in one model (Sujar et al. 2018, §3.1, rigging from labelled
// regions of the bones: "we estimate two orthogonal vectors and the bone rotation centre from a set of
// annotated vertices"), e.g. the OpenSim Rajagopal 2016 meshes assembled in its default pose: pelvis, legs,
// trunk and arms. The counterpart of skeleton_from_bones.h, which does the pelvis, legs and lumbar spine
// from a CT's label voxels.
//
// Sujar et al. 2018 annotates its vertex sets by hand (its supplementary Matlab code, which we do not have). Ours
// are found from the meshes alone, all in mm (LPS):
// - Hip: the femoral head is the femur's vertices within `acetabulumDistance` of the pelvis's surface
//   (points_near.h: the part facing the acetabulum); its least-squares sphere (sphere_fit.h) gives the
//   rotation centre.
// - Knee: the posterior condyles are the femur's vertices within `condyleReach` of the tibia's surface
//   (the distal femur) that lie behind the plane through their mean spanned by the femur's long axis and
//   the line through the hip centres. A least-squares cylinder through them (cylinder_fit.h, started from
//   that line) gives the flexion axis, and the centre is the point of that axis nearest their mean, i.e.
//   midway between the condyles: the posterior condyles' arcs are nearly circular about the flexion axis
//   (the "geometric centre axis" of the knee), while the distal arcs are flatter and would pull the
//   centre down and forward. One cylinder rather than a sphere per condyle because coarse meshes have too
//   few vertices per condyle for a sphere.
// - Ankle: the malleoli are the tibia's and the fibula's vertices within `malleolusTip` of their most
//   distal point along the tibia's long axis; the centre is midway between the two tips and the axis
//   runs through them (the clinical ankle axis through the malleoli).
// - Lumbar (L5/S1): the lowest lumbar end plate and the sacrum's base, as skeleton_from_bones.h finds a
//   disc: the spine's vertices within `discReach` of the sacrum's surface and the sacrum's within it of
//   the spine's, each counted from the two meshes' nearest approach (pointsNearest: placed meshes may
//   stand apart or overlap); the centre is midway between the two regions' means.
// - Shoulder: the humeral head is the humerus's vertices within `glenoidReach` of the rib cage and
//   scapulae mesh, counted from their nearest approach (the part facing the glenoid; a placement may
//   leave the humerus off its glenoid); its least-squares sphere gives the centre.
// - Elbow: the trochlea and capitulum are the humerus's vertices within `trochleaReach` of the forearm's
//   (ulna and radius) surface; a least-squares cylinder through them, started from the torso's left–right
//   line made orthogonal to the humerus's long axis, gives the flexion axis, the centre the axis point
//   nearest their mean.
// - Wrist: the styloids are the radius's and the ulna's vertices within `styloidTip` of their most
//   distal point along the forearm's long axis (as the malleoli); the centre is midway between the tips and
//   the axis runs through them.
// Frames, each from two directions made orthogonal (bone_frame.h), x to the left (for a long bone of the
// arm: its hinge axis, signed to the left), z superior or proximal at rest:
// - pelvis (root, the hip bones and sacrum as one rigid bone): at the midpoint of the hip centres; x from
//   the right hip centre to the left, z towards the sacrum's vertex mean (made orthogonal to x, so it
//   leans back by the pelvic tilt) as skeleton_from_bones.h does without a spine.
// - femur: at the hip centre; z the principal axis of its vertices (principal_axis.h) signed towards the
//   hip, x the knee axis.
// - tibia: at the knee centre; z the principal axis of its vertices (without the fibula) signed towards the
//   knee, x the knee axis.
// - talus: at the ankle centre; x the ankle axis, z the tibia's z (no talus mesh is needed).
// - torso (spine, ribs and scapulae, skull and jaw as one rigid bone, as OpenSim's torso body): at the
//   lumbar centre; x from the right shoulder centre to the left, z towards the torso's vertex mean.
// - humerus: at the shoulder centre; z its principal axis signed towards the shoulder, x the elbow axis.
// - ulna (the forearm, ulna and radius as one rigid bone: no radioulnar joint): at the elbow centre; z the
//   principal axis of both signed towards the elbow, x the elbow axis.
// - hand (carpals, metacarpals and phalanges as one rigid bone): at the wrist centre; x the wrist axis, z
//   from the hand's vertex mean towards the wrist.
// Tails (core/skeleton.h): the knee centre for a femur, the ankle centre for a tibia, the elbow centre for
// a humerus, the wrist centre for a forearm, none otherwise.
// Deviations from Sujar et al. 2018: regions by distance and extremity, not annotation; the ankle from the
// malleoli, not from the talus (on the OpenSim meshes cylinders through the talar trochlea facing the
// tibia missed the model's ankle centre by 5.6-13.7 mm and its axis by 10-25°, the malleoli by 2.4 mm and
// 22°: the talus has 99 vertices); one lumbar joint and no vertebrae above it (OpenSim gives the lumbar
// spine and thorax as one mesh, hat_spine, without vertebrae to chain), no neck; the shoulder girdle is
// rigid with the rib cage (OpenSim's scapulae are in hat_ribs_scap).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/posing/cylinder_fit.h"
#include "vesalius/posing/sphere_fit.h"

#include <map>
#include <string>
#include <vector>

namespace vesalius::posing {

// OpenSim's hand meshes of one side ("l" or "r"): the carpals, metacarpals and phalanges of Rajagopal 2016.
std::vector<std::string> openSimHand(const std::string& side);

struct SkeletonFromBoneMeshesOptions {
  // Each bone is the union of these meshes (keys of the `meshes` map); OpenSim's file stems by default.
  std::vector<std::string> pelvis{"r_pelvis", "l_pelvis", "sacrum"};
  std::vector<std::string> femurLeft{"l_femur"}, femurRight{"r_femur"};
  std::vector<std::string> tibiaLeft{"l_tibia"}, tibiaRight{"r_tibia"};
  std::vector<std::string> fibulaLeft{"l_fibula"}, fibulaRight{"r_fibula"};
  std::vector<std::string> torso{"hat_spine", "hat_ribs_scap", "hat_skull", "hat_jaw"};
  std::vector<std::string> humerusLeft{"humerus_lv"}, humerusRight{"humerus_rv"};
  std::vector<std::string> ulnaLeft{"ulna_lv"}, ulnaRight{"ulna_rv"};
  std::vector<std::string> radiusLeft{"radius_lv"}, radiusRight{"radius_rv"};
  std::vector<std::string> handLeft = openSimHand("l"), handRight = openSimHand("r");
  std::string sacrum = "sacrum";   // the pelvis mesh whose vertex mean sets the pelvis's z
  std::vector<std::string> spine{"hat_spine"};  // the torso meshes whose union meets the sacrum
  std::vector<std::string> scapulae{"hat_ribs_scap"};  // the torso meshes whose union holds the glenoids
  double acetabulumDistance = 6.0; // mm: femoral head vertices this close to the pelvis
  double condyleReach = 40.0;      // mm: distal femur vertices this close to the tibia
  double malleolusTip = 2.0;       // mm: malleolus vertices this close to their bone's distal end
  double discReach = 12.0;         // mm: spine and sacrum vertices this much beyond their nearest approach
  double glenoidReach = 15.0;      // mm: humerus vertices this much beyond its nearest approach to the glenoid
  double trochleaReach = 10.0;     // mm: distal humerus vertices this close to the forearm
  double styloidTip = 2.0;         // mm: styloid vertices this close to their bone's distal end
};

struct LegJoints {
  SphereFit femoralHead;
  CylinderFit knee;  // axis to the left
  Eigen::Vector3d medialMalleolus = Eigen::Vector3d::Zero(), lateralMalleolus = Eigen::Vector3d::Zero();
  Eigen::Vector3d ankleCentre = Eigen::Vector3d::Zero(), ankleAxis = Eigen::Vector3d::UnitX();  // axis: unit, left
  long headVertices = 0, condyleVertices = 0;  // region sizes the fits used
};

struct ArmJoints {
  SphereFit humeralHead;
  CylinderFit elbow;  // axis to the left
  Eigen::Vector3d radialStyloid = Eigen::Vector3d::Zero(), ulnarStyloid = Eigen::Vector3d::Zero();
  Eigen::Vector3d wristCentre = Eigen::Vector3d::Zero(), wristAxis = Eigen::Vector3d::UnitX();  // axis: unit, left
  long headVertices = 0, trochleaVertices = 0;  // region sizes the fits used
};

struct LumbarJoint {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  long spineVertices = 0, sacrumVertices = 0;  // the end plates' vertex counts
};

struct MeshSkeleton {
  // Joints: "pelvis" (root), then "femur_l", "tibia_l", "talus_l", "femur_r", "tibia_r", "talus_r", each a
  // child of the one before within a leg; "torso" (child of the pelvis), then "humerus_l", "ulna_l",
  // "hand_l", "humerus_r", "ulna_r", "hand_r", each a child of the one before within an arm (OpenSim's
  // body names; "ulna_l" carries the radius too). Rest frames as above.
  Skeleton skeleton;
  LegJoints left, right;
  LumbarJoint lumbar;
  ArmJoints leftArm, rightArm;
};

// The joints' names of MeshSkeleton::skeleton, in its order, before any mesh is read.
std::vector<std::string> meshSkeletonJoints();

// meshes: bone meshes by name, mm LPS, placed in one model. Throws BadInput naming `source` and the mesh
// if a mesh a bone needs is missing or empty, or if a joint's region (femoral head, posterior condyles,
// end plates, humeral head, trochlea and capitulum) has fewer than 8 vertices.
MeshSkeleton skeletonFromBoneMeshes(const std::map<std::string, TriMesh>& meshes,
                                    const SkeletonFromBoneMeshesOptions& options = {},
                                    const std::string& source = "bone meshes");

}  // namespace vesalius::posing
