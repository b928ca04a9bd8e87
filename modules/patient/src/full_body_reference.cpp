#include "vesalius/patient/full_body_reference.h"

#include "skin_distances.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/transfer/anatomy_checks.h"
#include "vesalius/transfer/body_frame.h"
#include "vesalius/transfer/bones_inside_skin.h"
#include "vesalius/transfer/bones_warped_into_skin.h"
#include "vesalius/transfer/skeleton_placement.h"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <memory>

namespace vesalius::patient {
namespace {

constexpr double kPi = 3.14159265358979323846;

// OpenSim bodies of the trunk (Dicko et al. 2013, §8: skull, spine, sternum, pelvis, rib cage move symmetrically).
bool isTrunkBody(const std::string& body) { return body == "pelvis" || body == "torso"; }

// A bone mesh's group (the bones that move by one map in §8): its OpenSim body, but for the skull and jaw,
// which Rajagopal's torso carries with the spine and rib cage: §8 gives each trunk bone a map of its own,
// and one trunk map scaled the skull with a muscular body's chest (determinant 1.9) into its face.
std::string boneGroup(const std::string& body, const std::string& mesh) {
  return body == "torso" && (mesh == "hat_skull" || mesh == "hat_jaw") ? io::kSkullGroup : body;
}

// The bones that move inside the skin together, by name: a trunk group (symmetric, Dicko et al. 2013, §8) as one,
// every other bone mesh alone (the hand's carpals apart from its digits, which the placement already fits
// bone by bone). Each tissue's unit name is in unitOfTissue. The skull and jaw (one symmetric unit) need
// the skin's mouth counted as inside (meshing/body_distance.h): 2,031 of their vertices lie in it, which
// no similarity of the skull leaves (docs/methods/skeleton-alignment.md).
std::map<std::string, std::vector<std::size_t>> unitsIntoSkin(const ReferenceAnatomy& anatomy,
                                                              std::map<std::string, std::string>& unitOfTissue) {
  std::map<std::string, std::vector<std::size_t>> units;
  for (std::size_t t = 0; t < anatomy.tissues.size(); ++t) {
    const ReferenceTissue& tissue = anatomy.tissues[t];
    unitOfTissue[tissue.name] = tissue.symmetric ? tissue.group : tissue.name;
    units[unitOfTissue[tissue.name]].push_back(t);
  }
  return units;
}

// The vertices of `tissues`, stacked in their order.
MatrixX3d stackedVertices(const ReferenceAnatomy& anatomy, const std::vector<std::size_t>& tissues) {
  MatrixX3d V(0, 3);
  for (const std::size_t t : tissues) {
    V.conservativeResize(V.rows() + anatomy.tissues[t].mesh.V.rows(), 3);
    V.bottomRows(anatomy.tissues[t].mesh.V.rows()) = anatomy.tissues[t].mesh.V;
  }
  return V;
}

// The joint centres (rows of `joints`) within reach of the bones V: a joint's centre lies within about a
// femoral head's radius (25 mm) of both bones that meet there.
MatrixX3d jointsOfBones(const MatrixX3d& V, const MatrixX3d& joints) {
  constexpr double kReachMm = 30.0;
  MatrixX3d near(0, 3);
  for (Eigen::Index j = 0; j < joints.rows(); ++j) {
    if ((V.rowwise() - joints.row(j)).rowwise().squaredNorm().minCoeff() > kReachMm * kReachMm) continue;
    near.conservativeResize(near.rows() + 1, 3);
    near.bottomRows(1) = joints.row(j);
  }
  return near;
}

// Step 3: each unit of bones moved inside the skin, `joints` (the placed joint centres) near it kept.
void moveBonesInsideSkin(FullBodyReference& reference, const MatrixX3d& joints) {
  ReferenceAnatomy& anatomy = reference.anatomy;
  const transfer::SkinDistanceFunction skin = skinDistances(anatomy.skin);
  std::map<std::string, std::string> unitOfTissue;
  for (const auto& [unit, members] : unitsIntoSkin(anatomy, unitOfTissue)) {
    const MatrixX3d V = stackedVertices(anatomy, members), near = jointsOfBones(V, joints);
    const transfer::InsideSkinCorrection c =
        transfer::correctionIntoSkin(V, near, skin, anatomy.tissues[members[0]].symmetric ? &anatomy.sagittal : nullptr);
    const transfer::InsideSkinWarp bend = transfer::warpIntoSkin(c.change.apply(V), skin);
    for (const std::size_t t : members) anatomy.tissues[t].mesh.V = bend.apply(c.change.apply(anatomy.tissues[t].mesh.V));
    for (ReferencePoint& p : anatomy.points)
      if (unitOfTissue.count(p.tissue) && unitOfTissue.at(p.tissue) == unit)
        p.position = bend.apply(c.change.apply(p.position).transpose()).transpose();
    const Eigen::Vector3d centroid = V.colwise().mean().transpose();
    BoneUnitIntoSkin u;
    u.unit = unit;
    u.outsideBefore = c.outsideBefore;
    u.outsideAfterChange = c.outsideAfter;
    u.outsideAfter = bend.outsideAfter;
    u.bendLargestMm = bend.largestMoveMm;
    u.scale = c.change.scale;
    u.turnDegrees = Eigen::AngleAxisd(c.change.rotation).angle() * 180.0 / kPi;
    u.centroidShiftMm = (c.change.apply(centroid) - centroid).norm();
    u.joints = near.rows();
    u.jointShiftMm = near.rows() ? (c.change.apply(near) - near).rowwise().norm().maxCoeff() : 0.0;
    reference.intoSkin.push_back(u);
    reference.outsideBefore += c.outsideBefore;
    reference.outsideAfter += bend.outsideAfter;
  }
}

// The joint centres of the placed model: each non-root body's origin (#bodies − roots by 3).
MatrixX3d placedJoints(const Skeleton& bodies, const transfer::SkeletonPlacement& placement) {
  MatrixX3d joints(0, 3);
  for (std::size_t b = 0; b < bodies.joints.size(); ++b) {
    if (bodies.joints[b].parent < 0) continue;
    joints.conservativeResize(joints.rows() + 1, 3);
    joints.bottomRows(1) = transfer::placeBodyPoints(bodies, placement, int(b), MatrixX3d::Zero(1, 3));
  }
  return joints;
}

// Step 4's organs were carried into this very skin (reference_organs.h), so they are added unmoved; in
// another body's skin they would lie wrong, which the skin's vertices tell (0.01 mm: OBJ keeps every digit).
void checkOrgansSkin(const TriMesh& skin, const ReferenceAnatomy& organs, const std::string& source) {
  constexpr double kSameSkinMm = 0.01;
  if (organs.skin.V.rows() != skin.V.rows() || (organs.skin.V - skin.V).rowwise().norm().maxCoeff() > kSameSkinMm)
    throw BadInput(source, "its organs were made for another skin than the reference's (" +
                               std::to_string(organs.skin.V.rows()) + " skin vertices against " +
                               std::to_string(skin.V.rows()) + ", or moved)");
}

}  // namespace

FullBodyReference buildFullBodyReference(const FullBodySources& sources, const std::string& skeletonSource) {
  if (sources.geometry.size() != sources.model.geometry.size() || sources.geometryNames.size() != sources.geometry.size())
    throw BadInput(skeletonSource, "full-body reference: one mesh and one name per geometry entry are needed");
  if (sources.organs) checkOrgansSkin(sources.skin, *sources.organs, sources.organsSource);
  FullBodyReference result;
  ReferenceAnatomy& anatomy = result.anatomy;
  anatomy.name = sources.name;
  anatomy.skin = sources.skin;
  std::map<std::string, Eigen::Vector3d> joints = transfer::jointPositions(sources.rig);
  for (const char* name : {"upperleg01.L", "foot.L", "upperleg01.R", "foot.R"})
    if (!joints.count(name)) throw BadInput(skeletonSource, std::string("no joint '") + name + "' (a MakeHuman default rig is needed)");
  const transfer::BodyFrame frame = transfer::computeBodyFrame(
      anatomy.skin.V, anatomy.skin.F, {joints.at("upperleg01.L"), joints.at("foot.L"), joints.at("upperleg01.R"), joints.at("foot.R")});
  joints["head-spine"] = frame.headSpineJoint;
  anatomy.sagittal = {frame.sagittalPoint, frame.sagittalNormal};
  result.headSlices = frame.headSlices;

  const MusculoskeletalModel& model = sources.model;
  const transfer::SkeletonCorrespondence correspondence = transfer::rajagopalToMakeHuman();
  const transfer::SkeletonPlacement placement = transfer::placeSkeleton(model.bodies, correspondence, joints, frame.axes());
  std::map<std::string, MatrixX3d> localMeshes;
  for (std::size_t m = 0; m < sources.geometry.size(); ++m) localMeshes[sources.geometryNames[m]] = sources.geometry[m].V;
  const std::map<std::string, SimilarityTransform> digits = transfer::placeDigits(
      model.bodies, placement, correspondence.digits, localMeshes, transfer::boneSegments(sources.rig));
  // Points of a body's frame (#P by 3) placed as its mesh `name` is: by the body's placement, or by the
  // digit's own fit.
  const auto placeAsMesh = [&](const std::string& name, int body, const MatrixX3d& local) {
    const auto digit = digits.find(name);
    return digit == digits.end() ? transfer::placeBodyPoints(model.bodies, placement, body, local)
                                 : digit->second.apply(transfer::restWorldPoints(model.bodies, body, local));
  };
  std::map<int, std::string> firstTissueOfBody;
  for (std::size_t m = 0; m < sources.geometry.size(); ++m) {
    const AttachedGeometry& g = model.geometry[m];
    const std::string& name = sources.geometryNames[m];
    const std::string& body = model.bodies.joints[std::size_t(g.body)].name;
    TriMesh mesh = sources.geometry[m];
    mesh.V = placeAsMesh(name, g.body, mesh.V);
    ReferenceTissue tissue{name, TissueKind::Bone, boneGroup(body, name), isTrunkBody(body), std::move(mesh)};
    firstTissueOfBody.emplace(g.body, tissue.name);
    anatomy.tissues.push_back(std::move(tissue));
  }
  const std::vector<MatrixX3d> paths = transfer::placeMusclePaths(model.bodies, placement, model.muscles);
  for (std::size_t m = 0; m < model.muscles.size(); ++m)
    for (std::size_t p = 0; p < model.muscles[m].path.size(); ++p) {
      const auto tissue = firstTissueOfBody.find(model.muscles[m].path[p].body);
      anatomy.points.push_back({model.muscles[m].name + "/" + model.muscles[m].path[p].name,
                                tissue == firstTissueOfBody.end() ? "" : tissue->second,
                                paths[m].row(Eigen::Index(p)).transpose()});
    }
  // The joint centres, which the transfer carries too (Dicko et al. 2013, §8): each non-root body's origin, named
  // joint/BODY and fixed to the body's first mesh.
  for (std::size_t b = 0; b < model.bodies.joints.size(); ++b) {
    if (model.bodies.joints[b].parent < 0) continue;
    const auto first = firstTissueOfBody.find(int(b));
    const std::string tissue = first == firstTissueOfBody.end() ? "" : first->second;
    anatomy.points.push_back({"joint/" + model.bodies.joints[b].name, tissue,
                              placeAsMesh(tissue, int(b), MatrixX3d::Zero(1, 3)).row(0).transpose()});
  }
  moveBonesInsideSkin(result, placedJoints(model.bodies, placement));
  if (sources.organs)
    for (const ReferenceTissue& t : sources.organs->tissues)
      if (t.kind == TissueKind::Organ || t.kind == TissueKind::Muscle) anatomy.tissues.push_back(t);
  return result;
}

}  // namespace vesalius::patient
