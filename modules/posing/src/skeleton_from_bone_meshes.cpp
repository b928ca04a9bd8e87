#include "vesalius/posing/skeleton_from_bone_meshes.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/bone_frame.h"
#include "vesalius/posing/points_near.h"
#include "vesalius/posing/principal_axis.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <vector>

namespace vesalius::posing {
namespace {

constexpr long kMinimumRegion = 8;  // vertices a region needs: a sphere or cylinder fit with some redundancy

struct Leg {
  TriMesh femur, tibia, fibula;
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

}  // namespace

MeshSkeleton skeletonFromBoneMeshes(const std::map<std::string, TriMesh>& meshes, const SkeletonFromBoneMeshesOptions& o,
                                    const std::string& source) {
  const auto bone = [&](const std::vector<std::string>& names, const std::string& what) {
    if (names.empty()) throw UsageError("skeletonFromBoneMeshes: no meshes named for the " + what);
    TriMesh all;
    for (const std::string& name : names) {
      const auto found = meshes.find(name);
      if (found == meshes.end() || found->second.V.rows() == 0 || found->second.F.rows() == 0)
        throw BadInput(source, "has no mesh '" + name + "' (" + what + ")");
      all = all.V.rows() == 0 ? found->second : concatenate(all, found->second);
    }
    return all;
  };
  const auto join = [](const std::vector<std::string>& names) {
    std::string s;
    for (const std::string& name : names) s += (s.empty() ? "" : "+") + name;
    return s;
  };
  const TriMesh pelvis = bone(o.pelvis, "pelvis");
  if (std::find(o.pelvis.begin(), o.pelvis.end(), o.sacrum) == o.pelvis.end())
    throw UsageError("skeletonFromBoneMeshes: the sacrum '" + o.sacrum + "' is not one of the pelvis meshes");
  const Leg legs[2] = {{bone(o.femurLeft, "left femur"), bone(o.tibiaLeft, "left tibia"), bone(o.fibulaLeft, "left fibula")},
                       {bone(o.femurRight, "right femur"), bone(o.tibiaRight, "right tibia"), bone(o.fibulaRight, "right fibula")}};
  const std::string femurNames[2] = {join(o.femurLeft), join(o.femurRight)};

  MeshSkeleton out;
  LegJoints* joints[2] = {&out.left, &out.right};
  for (int side = 0; side < 2; ++side) {
    const MatrixX3d head = pointsNear(legs[side].femur.V, pelvis, o.acetabulumDistance);
    joints[side]->headVertices = checkedCount(head, femurNames[side], "femoral head (within " +
                                              std::to_string(o.acetabulumDistance) + " mm of the pelvis)", source);
    joints[side]->femoralHead = fitSphere(head);
  }
  const Eigen::Vector3d left = out.left.femoralHead.centre - out.right.femoralHead.centre;
  const Eigen::Vector3d origin = (out.left.femoralHead.centre + out.right.femoralHead.centre) / 2;
  const Eigen::Matrix3d pelvisAxes = boneFrame(0, left, 2, centroid(meshes.at(o.sacrum).V) - origin);

  std::vector<Eigen::Isometry3d> world{placedFrame(pelvisAxes, origin)};
  out.skeleton.joints.push_back({"pelvis", -1});
  const char* suffix[2] = {"_l", "_r"};
  for (int side = 0; side < 2; ++side) {
    const Leg& leg = legs[side];
    LegJoints& j = *joints[side];
    const Eigen::Vector3d hip = j.femoralHead.centre;
    const Eigen::Vector3d femurZ = principalAxis(leg.femur.V, hip - centroid(leg.femur.V));
    const MatrixX3d distal = pointsNear(leg.femur.V, leg.tibia, o.condyleReach);
    const Eigen::Vector3d behind = femurZ.cross(left), middle = distal.rows() ? centroid(distal) : hip;
    const MatrixX3d condyles = rowsWhere(distal, [&](const Eigen::Vector3d& p) { return (p - middle).dot(behind) > 0; });
    j.condyleVertices = checkedCount(condyles, femurNames[side], "posterior condyles", source);
    j.knee = fitCylinder(condyles, left);
    const Eigen::Vector3d knee = j.knee.point;
    const Eigen::Vector3d tibiaZ = principalAxis(leg.tibia.V, knee - centroid(leg.tibia.V));
    j.medialMalleolus = distalTip(leg.tibia.V, tibiaZ, o.malleolusTip);
    j.lateralMalleolus = distalTip(leg.fibula.V, tibiaZ, o.malleolusTip);
    j.ankleCentre = (j.medialMalleolus + j.lateralMalleolus) / 2;
    j.ankleAxis = (j.medialMalleolus - j.lateralMalleolus).normalized();
    if (j.ankleAxis.dot(left) < 0) j.ankleAxis = -j.ankleAxis;
    const Eigen::Vector3d ankle = j.ankleCentre;
    const Eigen::Isometry3d frames[3] = {placedFrame(boneFrame(2, femurZ, 0, j.knee.axis), hip),
                                         placedFrame(boneFrame(2, tibiaZ, 0, j.knee.axis), knee),
                                         placedFrame(boneFrame(0, j.ankleAxis, 2, tibiaZ), ankle)};
    const Eigen::Vector3d tails[3] = {frames[0].inverse() * knee, frames[1].inverse() * ankle, Eigen::Vector3d::Zero()};
    const char* bodies[3] = {"femur", "tibia", "talus"};
    for (int b = 0; b < 3; ++b) {
      const int parent = b == 0 ? 0 : int(out.skeleton.joints.size()) - 1;
      Joint joint{std::string(bodies[b]) + suffix[side], parent};
      joint.restLocal = world[std::size_t(parent)].inverse() * frames[b];
      joint.tail = tails[b];
      out.skeleton.joints.push_back(joint);
      world.push_back(frames[b]);
    }
  }
  out.skeleton.joints[0].restLocal = world[0];
  out.skeleton.validate(source);
  return out;
}

}  // namespace vesalius::posing
