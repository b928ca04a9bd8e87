// A skeleton of the lower body from bone meshes placed in one model (seed 001 §3.1, rigging from labelled
// regions of the bones: "we estimate two orthogonal vectors and the bone rotation centre from a set of
// annotated vertices"), e.g. the OpenSim Rajagopal 2016 meshes assembled in its default pose. The
// counterpart of skeleton_from_bones.h, which does the same from a CT's label voxels.
//
// The seed annotates its vertex sets by hand (its supplementary Matlab code, which we do not have). Ours
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
// Frames, each from two directions made orthogonal (bone_frame.h), x to the left, z superior at rest:
// - pelvis (root, the hip bones and sacrum as one rigid bone): at the midpoint of the hip centres; x from
//   the right hip centre to the left, z towards the sacrum's vertex mean (made orthogonal to x, so it
//   leans back by the pelvic tilt) as skeleton_from_bones.h does without a spine.
// - femur: at the hip centre; z the principal axis of its vertices (principal_axis.h) signed towards the
//   hip, x the knee axis.
// - tibia: at the knee centre; z the principal axis of its vertices (without the fibula) signed towards the
//   knee, x the knee axis.
// - talus: at the ankle centre; x the ankle axis, z the tibia's z (no talus mesh is needed).
// Tails (core/skeleton.h): the knee centre for a femur, the ankle centre for a tibia, none otherwise.
// Deviations from the seed: regions by distance and extremity, not annotation; the ankle from the
// malleoli, not from the talus (on the OpenSim meshes cylinders through the talar trochlea facing the
// tibia missed the model's ankle centre by 5.6-13.7 mm and its axis by 10-25°, the malleoli by 2.4 mm and
// 22°: the talus has 99 vertices); no spine (OpenSim gives the lumbar spine and thorax as one mesh,
// hat_spine, without vertebrae to chain).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"
#include "vesalius/posing/cylinder_fit.h"
#include "vesalius/posing/sphere_fit.h"

#include <map>
#include <string>
#include <vector>

namespace vesalius::posing {

struct SkeletonFromBoneMeshesOptions {
  // Each bone is the union of these meshes (keys of the `meshes` map); OpenSim's file stems by default.
  std::vector<std::string> pelvis{"r_pelvis", "l_pelvis", "sacrum"};
  std::vector<std::string> femurLeft{"l_femur"}, femurRight{"r_femur"};
  std::vector<std::string> tibiaLeft{"l_tibia"}, tibiaRight{"r_tibia"};
  std::vector<std::string> fibulaLeft{"l_fibula"}, fibulaRight{"r_fibula"};
  std::string sacrum = "sacrum";   // the pelvis mesh whose vertex mean sets the pelvis's z
  double acetabulumDistance = 6.0; // mm: femoral head vertices this close to the pelvis
  double condyleReach = 40.0;      // mm: distal femur vertices this close to the tibia
  double malleolusTip = 2.0;       // mm: malleolus vertices this close to their bone's distal end
};

struct LegJoints {
  SphereFit femoralHead;
  CylinderFit knee;  // axis to the left
  Eigen::Vector3d medialMalleolus = Eigen::Vector3d::Zero(), lateralMalleolus = Eigen::Vector3d::Zero();
  Eigen::Vector3d ankleCentre = Eigen::Vector3d::Zero(), ankleAxis = Eigen::Vector3d::UnitX();  // axis: unit, left
  long headVertices = 0, condyleVertices = 0;  // region sizes the fits used
};

struct MeshSkeleton {
  // Joints: "pelvis" (root), then "femur_l", "tibia_l", "talus_l", "femur_r", "tibia_r", "talus_r"
  // (OpenSim's body names), each a child of the one before within a leg; rest frames as above.
  Skeleton skeleton;
  LegJoints left, right;
};

// meshes: bone meshes by name, mm LPS, placed in one model. Throws BadInput naming `source` and the mesh
// if a mesh a bone needs is missing or empty, or if a femoral head or the posterior condyles have fewer
// than 8 vertices.
MeshSkeleton skeletonFromBoneMeshes(const std::map<std::string, TriMesh>& meshes,
                                    const SkeletonFromBoneMeshesOptions& options = {},
                                    const std::string& source = "bone meshes");

}  // namespace vesalius::posing
