#include "vesalius/posing/skeleton_from_bone_meshes.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/bone_frame.h"
#include "vesalius/posing/points_near.h"
#include "vesalius/posing/principal_axis.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <tuple>
#include <utility>
#include <vector>

namespace vesalius::posing {
namespace {

constexpr long kMinimumRegion = 8;  // vertices a region needs: a sphere or cylinder fit with some redundancy

struct Leg {
  TriMesh femur, tibia, fibula;
};

struct Arm {
  TriMesh humerus, ulna, radius, hand;
};

// A limb's bodies from its root down: their rest frames and tails (world).
const std::vector<const char*> kLegBodies{"femur", "tibia", "talus"}, kArmBodies{"humerus", "ulna", "hand"};

struct Chain {
  std::vector<const char*> bodies;
  std::vector<Eigen::Isometry3d> frames;
  std::vector<Eigen::Vector3d> tails;  // world; zero for none
};

Eigen::Vector3d centroid(const MatrixX3d& P) { return P.colwise().mean().transpose(); }

// The rows of P that `keep` accepts.
template <class Keep>
MatrixX3d rowsWhere(const MatrixX3d& P, Keep keep) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    if (keep(Eigen::Vector3d(P.row(r).transpose()))) kept.push_back(r);
  return P(kept, Eigen::all);
}

// A region's vertices, checked for the count a fit needs.
long checkedCount(const MatrixX3d& region, const std::string& bone, const std::string& what, const std::string& source) {
  if (region.rows() < kMinimumRegion)
    throw BadInput(source, "'" + bone + "' has " + std::to_string(region.rows()) + " vertices in its " + what +
                               " (a fit needs " + std::to_string(kMinimumRegion) + ")");
  return long(region.rows());
}

// The mean of V's rows within `tip` of their lowest along `up`.
Eigen::Vector3d distalTip(const MatrixX3d& V, const Eigen::Vector3d& up, double tip) {
  const Eigen::VectorXd height = V * up;
  const double lowest = height.minCoeff();
  return centroid(rowsWhere(V, [&](const Eigen::Vector3d& p) { return p.dot(up) <= lowest + tip; }));
}

// A hinge through two bony tips (the malleoli, the styloids): centre midway, axis through them to the left.
std::pair<Eigen::Vector3d, Eigen::Vector3d> axisThroughTips(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                            const Eigen::Vector3d& left) {
  const Eigen::Vector3d axis = (a - b).normalized();
  return {(a + b) / 2, axis.dot(left) < 0 ? Eigen::Vector3d(-axis) : axis};
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& name : names) s += (s.empty() ? "" : "+") + name;
  return s;
}

// The union of the named meshes; BadInput naming `source` and the mesh if one is missing or empty.
TriMesh boneOf(const std::map<std::string, TriMesh>& meshes, const std::vector<std::string>& names, const std::string& what,
               const std::string& source) {
  if (names.empty()) throw UsageError("skeletonFromBoneMeshes: no meshes named for the " + what);
  TriMesh all;
  for (const std::string& name : names) {
    const auto found = meshes.find(name);
    if (found == meshes.end() || found->second.V.rows() == 0 || found->second.F.rows() == 0)
      throw BadInput(source, "has no mesh '" + name + "' (" + what + ")");
    all = all.V.rows() == 0 ? found->second : concatenate(all, found->second);
  }
  return all;
}

// The union of `names`, each of which must be one of `bone`'s meshes (options.spine of the torso, ...).
TriMesh partOf(const std::map<std::string, TriMesh>& meshes, const std::vector<std::string>& bone,
               const std::vector<std::string>& names, const std::string& what, const std::string& source) {
  for (const std::string& name : names)
    if (std::find(bone.begin(), bone.end(), name) == bone.end())
      throw UsageError("skeletonFromBoneMeshes: the " + what + " '" + name + "' is not one of its bone's meshes");
  return boneOf(meshes, names, what, source);
}

// The femoral head facing the acetabulum and its sphere (header: Hip).
void fitHip(LegJoints& j, const Leg& leg, const TriMesh& pelvis, const SkeletonFromBoneMeshesOptions& o,
            const std::string& femurName, const std::string& source) {
  const MatrixX3d head = pointsNear(leg.femur.V, pelvis, o.acetabulumDistance);
  j.headVertices = checkedCount(head, femurName, "femoral head (within " + std::to_string(o.acetabulumDistance) +
                                                     " mm of the pelvis)", source);
  j.femoralHead = fitSphere(head);
}

// Knee centre and axis, ankle centre and axis of one leg whose hip is fitted (header: Knee, Ankle).
void fitKneeAndAnkle(LegJoints& j, const Leg& leg, const Eigen::Vector3d& left, const SkeletonFromBoneMeshesOptions& o,
                     const std::string& femurName, const std::string& source) {
  const Eigen::Vector3d hip = j.femoralHead.centre;
  const Eigen::Vector3d femurZ = principalAxis(leg.femur.V, hip - centroid(leg.femur.V));
  const MatrixX3d distal = pointsNear(leg.femur.V, leg.tibia, o.condyleReach);
  const Eigen::Vector3d behind = femurZ.cross(left), middle = distal.rows() ? centroid(distal) : hip;
  const MatrixX3d condyles = rowsWhere(distal, [&](const Eigen::Vector3d& p) { return (p - middle).dot(behind) > 0; });
  j.condyleVertices = checkedCount(condyles, femurName, "posterior condyles", source);
  j.knee = fitCylinder(condyles, left);
  const Eigen::Vector3d tibiaZ = principalAxis(leg.tibia.V, j.knee.point - centroid(leg.tibia.V));
  j.medialMalleolus = distalTip(leg.tibia.V, tibiaZ, o.malleolusTip);
  j.lateralMalleolus = distalTip(leg.fibula.V, tibiaZ, o.malleolusTip);
  std::tie(j.ankleCentre, j.ankleAxis) = axisThroughTips(j.medialMalleolus, j.lateralMalleolus, left);
}

Chain legChain(const Leg& leg, const LegJoints& j) {
  const Eigen::Vector3d hip = j.femoralHead.centre, knee = j.knee.point;
  const Eigen::Vector3d femurZ = principalAxis(leg.femur.V, hip - centroid(leg.femur.V));
  const Eigen::Vector3d tibiaZ = principalAxis(leg.tibia.V, knee - centroid(leg.tibia.V));
  return {kLegBodies,
          {placedFrame(boneFrame(2, femurZ, 0, j.knee.axis), hip), placedFrame(boneFrame(2, tibiaZ, 0, j.knee.axis), knee),
           placedFrame(boneFrame(0, j.ankleAxis, 2, tibiaZ), j.ankleCentre)},
          {knee, j.ankleCentre, Eigen::Vector3d::Zero()}};
}

// The L5/S1 disc between the spine and sacrum meshes (header: Lumbar).
LumbarJoint fitLumbar(const TriMesh& spine, const TriMesh& sacrum, const SkeletonFromBoneMeshesOptions& o,
                      const std::string& source) {
  const MatrixX3d upper = pointsNearest(spine.V, sacrum, o.discReach);
  const MatrixX3d lower = pointsNearest(sacrum.V, spine, o.discReach);
  LumbarJoint j;
  j.spineVertices = checkedCount(upper, joined(o.spine), "lowest end plate (facing '" + o.sacrum + "')", source);
  j.sacrumVertices = checkedCount(lower, o.sacrum, "base (facing '" + joined(o.spine) + "')", source);
  j.centre = (centroid(upper) + centroid(lower)) / 2;
  return j;
}

// The humeral head facing the glenoid and its sphere (header: Shoulder).
void fitShoulder(ArmJoints& j, const Arm& arm, const TriMesh& scapulae, const SkeletonFromBoneMeshesOptions& o,
                 const std::string& humerusName, const std::string& source) {
  const MatrixX3d head = pointsNearest(arm.humerus.V, scapulae, o.glenoidReach);
  j.headVertices = checkedCount(head, humerusName, "humeral head (facing '" + joined(o.scapulae) + "')", source);
  j.humeralHead = fitSphere(head);
}

// Elbow centre and axis, wrist centre and axis of one arm whose shoulder is fitted (header: Elbow, Wrist).
void fitForearm(ArmJoints& j, const Arm& arm, const Eigen::Vector3d& left, const SkeletonFromBoneMeshesOptions& o,
                const std::string& humerusName, const std::string& source) {
  const Eigen::Vector3d shoulder = j.humeralHead.centre;
  const Eigen::Vector3d humerusZ = principalAxis(arm.humerus.V, shoulder - centroid(arm.humerus.V));
  const TriMesh forearm = concatenate(arm.ulna, arm.radius);
  const MatrixX3d trochlea = pointsNear(arm.humerus.V, forearm, o.trochleaReach);
  j.trochleaVertices = checkedCount(trochlea, humerusName, "trochlea and capitulum (within " +
                                                              std::to_string(o.trochleaReach) + " mm of the forearm)", source);
  j.elbow = fitCylinder(trochlea, left - left.dot(humerusZ) * humerusZ);
  const Eigen::Vector3d forearmZ = principalAxis(forearm.V, j.elbow.point - centroid(forearm.V));
  j.radialStyloid = distalTip(arm.radius.V, forearmZ, o.styloidTip);
  j.ulnarStyloid = distalTip(arm.ulna.V, forearmZ, o.styloidTip);
  std::tie(j.wristCentre, j.wristAxis) = axisThroughTips(j.radialStyloid, j.ulnarStyloid, left);
}

Chain armChain(const Arm& arm, const ArmJoints& j) {
  const Eigen::Vector3d shoulder = j.humeralHead.centre, elbow = j.elbow.point, wrist = j.wristCentre;
  const Eigen::Vector3d humerusZ = principalAxis(arm.humerus.V, shoulder - centroid(arm.humerus.V));
  const TriMesh forearm = concatenate(arm.ulna, arm.radius);
  const Eigen::Vector3d forearmZ = principalAxis(forearm.V, elbow - centroid(forearm.V));
  return {kArmBodies,
          {placedFrame(boneFrame(2, humerusZ, 0, j.elbow.axis), shoulder),
           placedFrame(boneFrame(2, forearmZ, 0, j.elbow.axis), elbow),
           placedFrame(boneFrame(0, j.wristAxis, 2, wrist - centroid(arm.hand.V)), wrist)},
          {elbow, wrist, Eigen::Vector3d::Zero()}};
}

// Appends the chain's joints (suffixed) below joint `parent`, each a child of the one before.
void appendChain(Skeleton& skeleton, std::vector<Eigen::Isometry3d>& world, int parent, const Chain& chain,
                 const std::string& suffix) {
  for (std::size_t b = 0; b < chain.bodies.size(); ++b) {
    Joint joint{std::string(chain.bodies[b]) + suffix, parent};
    joint.restLocal = world[std::size_t(parent)].inverse() * chain.frames[b];
    joint.tail = chain.tails[b].isZero() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(chain.frames[b].inverse() * chain.tails[b]);
    parent = int(skeleton.joints.size());
    skeleton.joints.push_back(joint);
    world.push_back(chain.frames[b]);
  }
}

}  // namespace

std::vector<std::string> openSimHand(const std::string& side) {
  std::vector<std::string> names;
  for (const char* carpal : {"scaphoid", "lunate", "triquetrum", "pisiform", "trapezium", "trapezoid", "capitate", "hamate"})
    names.push_back(std::string(carpal) + "_" + side + "vs");
  for (int m = 1; m <= 5; ++m) names.push_back("metacarpal" + std::to_string(m) + "_" + side + "vs");
  for (const char* thumb : {"proximal", "distal"}) names.push_back(std::string("thumb_") + thumb + "_" + side + "vs");
  for (const char* finger : {"index", "middle", "ring", "little"})
    for (const char* phalanx : {"proximal", "medial", "distal"})
      names.push_back(std::string(finger) + "_" + phalanx + "_" + side + "vs");
  return names;
}

std::vector<std::string> meshSkeletonJoints() {
  std::vector<std::string> joints{"pelvis"};
  for (const char* side : {"_l", "_r"})
    for (const char* body : kLegBodies) joints.push_back(body + std::string(side));
  joints.push_back("torso");
  for (const char* side : {"_l", "_r"})
    for (const char* body : kArmBodies) joints.push_back(body + std::string(side));
  return joints;
}

MeshSkeleton skeletonFromBoneMeshes(const std::map<std::string, TriMesh>& meshes, const SkeletonFromBoneMeshesOptions& o,
                                    const std::string& source) {
  const auto bone = [&](const std::vector<std::string>& names, const std::string& what) {
    return boneOf(meshes, names, what, source);
  };
  const TriMesh pelvis = bone(o.pelvis, "pelvis"), torso = bone(o.torso, "torso");
  const TriMesh sacrum = partOf(meshes, o.pelvis, {o.sacrum}, "sacrum", source);
  const TriMesh spine = partOf(meshes, o.torso, o.spine, "spine", source);
  const TriMesh scapulae = partOf(meshes, o.torso, o.scapulae, "rib cage and scapulae", source);
  const Leg legs[2] = {{bone(o.femurLeft, "left femur"), bone(o.tibiaLeft, "left tibia"), bone(o.fibulaLeft, "left fibula")},
                       {bone(o.femurRight, "right femur"), bone(o.tibiaRight, "right tibia"), bone(o.fibulaRight, "right fibula")}};
  const Arm arms[2] = {{bone(o.humerusLeft, "left humerus"), bone(o.ulnaLeft, "left ulna"), bone(o.radiusLeft, "left radius"),
                        bone(o.handLeft, "left hand")},
                       {bone(o.humerusRight, "right humerus"), bone(o.ulnaRight, "right ulna"),
                        bone(o.radiusRight, "right radius"), bone(o.handRight, "right hand")}};
  const std::string femurNames[2] = {joined(o.femurLeft), joined(o.femurRight)};
  const std::string humerusNames[2] = {joined(o.humerusLeft), joined(o.humerusRight)};

  MeshSkeleton out;
  LegJoints* legJoints[2] = {&out.left, &out.right};
  for (int side = 0; side < 2; ++side) fitHip(*legJoints[side], legs[side], pelvis, o, femurNames[side], source);
  const Eigen::Vector3d hipLeft = out.left.femoralHead.centre, hipRight = out.right.femoralHead.centre;
  const Eigen::Vector3d left = hipLeft - hipRight;
  for (int side = 0; side < 2; ++side) fitKneeAndAnkle(*legJoints[side], legs[side], left, o, femurNames[side], source);
  out.lumbar = fitLumbar(spine, sacrum, o, source);
  ArmJoints* armJoints[2] = {&out.leftArm, &out.rightArm};
  for (int side = 0; side < 2; ++side) fitShoulder(*armJoints[side], arms[side], scapulae, o, humerusNames[side], source);
  const Eigen::Vector3d shoulderLeft = out.leftArm.humeralHead.centre - out.rightArm.humeralHead.centre;
  for (int side = 0; side < 2; ++side) fitForearm(*armJoints[side], arms[side], shoulderLeft, o, humerusNames[side], source);

  const Eigen::Vector3d origin = (hipLeft + hipRight) / 2;
  std::vector<Eigen::Isometry3d> world{placedFrame(boneFrame(0, left, 2, centroid(sacrum.V) - origin), origin)};
  out.skeleton.joints.push_back({"pelvis", -1});
  appendChain(out.skeleton, world, 0, legChain(legs[0], out.left), "_l");
  appendChain(out.skeleton, world, 0, legChain(legs[1], out.right), "_r");
  const Chain trunk{{"torso"},
                    {placedFrame(boneFrame(0, shoulderLeft, 2, centroid(torso.V) - out.lumbar.centre), out.lumbar.centre)},
                    {Eigen::Vector3d::Zero()}};
  appendChain(out.skeleton, world, 0, trunk, "");
  const int torsoJoint = int(out.skeleton.joints.size()) - 1;
  appendChain(out.skeleton, world, torsoJoint, armChain(arms[0], out.leftArm), "_l");
  appendChain(out.skeleton, world, torsoJoint, armChain(arms[1], out.rightArm), "_r");
  out.skeleton.joints[0].restLocal = world[0];
  out.skeleton.validate(source);
  return out;
}

}  // namespace vesalius::posing
