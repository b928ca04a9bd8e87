// Per-body similarity placement of a musculoskeletal model inside a skin (skeleton_placement.h).
#include "vesalius/transfer/skeleton_placement.h"

#include "vesalius/core/error.h"
#include "vesalius/core/principal_axes.h"

#include <Eigen/Geometry>

#include <cmath>

namespace vesalius::transfer {

namespace {

BodyCorrespondence pairs(std::string body, std::vector<std::string> model, std::vector<std::string> skin) {
  return {std::move(body), std::move(model), std::move(skin)};
}

void addSide(SkeletonCorrespondence& c, const std::string& s, const std::string& S) {
  // The hip on the placed pelvis's hip centre, not MakeHuman's (31.6 mm lateral of it): the femoral head
  // in its acetabulum.
  c.bodies.push_back(pairs("femur_" + s, {"femur_" + s, "tibia_" + s}, {kParentPlaced, "lowerleg01." + S}));
  c.bodies.push_back(pairs("tibia_" + s, {"tibia_" + s, "talus_" + s}, {"lowerleg01." + S, "foot." + S}));
  c.bodies.push_back(pairs("patella_" + s, {}, {}));
  for (const char* foot : {"talus_", "calcn_"})
    c.bodies.push_back(pairs(foot + s, {"talus_" + s, "toes_" + s}, {"foot." + S, "toe3-1." + S}));
  c.bodies.push_back(pairs("toes_" + s, {"toes_" + s}, {"toe3-1." + S}));
  c.bodies.push_back(pairs("humerus_" + s, {"humerus_" + s, "ulna_" + s}, {"upperarm01." + S, "lowerarm01." + S}));
  for (const char* forearm : {"ulna_", "radius_"})
    c.bodies.push_back(pairs(forearm + s, {"ulna_" + s, "hand_" + s}, {"lowerarm01." + S, "wrist." + S}));
  c.bodies.push_back(
      pairs("hand_" + s, {"hand_" + s, "mcp2_" + s, "mcp5_" + s}, {"wrist." + S, "finger2-1." + S, "finger5-1." + S}));
}

struct PointLookup {
  const Skeleton& model;
  const std::vector<Eigen::Isometry3d>& world;
  const SkeletonCorrespondence& correspondence;
  const std::map<std::string, Eigen::Vector3d>& targets;

  Eigen::Vector3d modelPoint(const std::string& name) const {
    const int b = model.find(name);
    if (b >= 0) return world[std::size_t(b)].translation();
    for (const ModelLandmark& l : correspondence.landmarks) {
      if (l.name != name) continue;
      const int body = model.find(l.body);
      if (body < 0)
        throw BadInput("", "skeleton placement: landmark '" + name + "' is on unknown body '" + l.body + "'");
      return world[std::size_t(body)] * l.offset;
    }
    throw BadInput("", "skeleton placement: no body or landmark '" + name + "' in the model");
  }
  // The skin point `name`, or for kParentPlaced the model point x as `parent` (this pass's) placed it.
  Eigen::Vector3d target(const std::string& name, const Eigen::Vector3d& x, const SimilarityTransform* parent,
                         const std::string& body) const {
    if (name == kParentPlaced) {
      if (!parent) throw BadInput("", "skeleton placement: root body '" + body + "' has no parent joint to target");
      return parent->apply(x);
    }
    auto it = targets.find(name);
    if (it == targets.end()) throw BadInput("", "skeleton placement: no target point '" + name + "'");
    return it->second;
  }
};

// Two pairs: the bone's axis a→b turned onto A→B from the reference rotation, scaled to length.
SimilarityTransform twoPointFit(const MatrixX3d& from, const MatrixX3d& to, const Eigen::Matrix3d& reference,
                                     const std::string& body) {
  const Eigen::Vector3d a = from.row(1) - from.row(0), b = to.row(1) - to.row(0);
  if (!(a.norm() > 1e-9 && b.norm() > 1e-9))
    throw BadInput("", "skeleton placement: the two joints of '" + body + "' coincide");
  SimilarityTransform t;
  t.scale = b.norm() / a.norm();
  t.rotation = Eigen::Quaterniond::FromTwoVectors(reference * a, b).toRotationMatrix() * reference;
  t.translation = 0.5 * (to.row(0) + to.row(1)).transpose() -
                  t.scale * t.rotation * (0.5 * (from.row(0) + from.row(1)).transpose());
  return t;
}

SimilarityTransform fitPairs(const MatrixX3d& from, const MatrixX3d& to, const SimilarityTransform* parent,
                                  const Eigen::Matrix3d& skinAxes, const std::string& body) {
  SimilarityTransform reference;
  if (parent)
    reference = *parent;
  else
    reference.rotation = skinAxes;
  if (from.rows() >= 3) return fitSimilarity(from, to, Eigen::VectorXd(), true);
  if (from.rows() == 2) return twoPointFit(from, to, reference.rotation, body);
  if (from.rows() == 0 && !parent)
    throw BadInput("", "skeleton placement: root body '" + body + "' has no point pairs");
  if (from.rows() == 1)
    reference.translation = to.row(0).transpose() - reference.scale * reference.rotation * from.row(0).transpose();
  return reference;
}

// The pairs' fit, with the scale replaced by `scale` (> 0) and the centroids kept together.
SimilarityTransform fitBody(const MatrixX3d& from, const MatrixX3d& to, const SimilarityTransform* parent,
                                 const Eigen::Matrix3d& skinAxes, const std::string& body, double scale) {
  SimilarityTransform t = fitPairs(from, to, parent, skinAxes, body);
  if (scale > 0 && from.rows() > 0) {
    t.scale = scale;
    t.translation = to.colwise().mean().transpose() - scale * t.rotation * from.colwise().mean().transpose();
  }
  return t;
}

// A digit bone's ends on its principal axis, the distal one away from `from`.
struct BoneEnds {
  Eigen::Vector3d proximal, distal, centroid;
};

BoneEnds boneEnds(const MatrixX3d& V, const Eigen::Vector3d& from, std::size_t bone) {
  if (V.rows() < 3) throw BadInput("", "digit joints: bone " + std::to_string(bone) + " has fewer than 3 vertices");
  const PrincipalAxes a = principalAxes(V);
  const Eigen::Vector3d centroid = a.centroid;
  Eigen::Vector3d axis = a.axes.col(0);
  if (axis.dot(centroid - from) < 0) axis = -axis;
  const Eigen::VectorXd along = (V.rowwise() - centroid.transpose()) * axis;
  return {centroid + along.minCoeff() * axis, centroid + along.maxCoeff() * axis, centroid};
}

// The digit's bones (vertices in the rest pose, world) from the correspondence's mesh names.
std::vector<MatrixX3d> digitBones(const Skeleton& model, int body, const DigitCorrespondence& digit,
                                  const std::map<std::string, MatrixX3d>& localMeshes) {
  std::vector<MatrixX3d> bones;
  for (const std::string& name : digit.bones) {
    const auto it = localMeshes.find(name);
    if (it == localMeshes.end())
      throw BadInput("", "skeleton placement: no mesh '" + name + "' on body '" + digit.body + "'");
    bones.push_back(restWorldPoints(model, body, it->second));
  }
  return bones;
}

// One digit's bones onto its skin bones (placeDigits), turning from `previous` (the placed body).
void placeDigitBones(const MatrixX3d& joints, const DigitCorrespondence& digit,
                     const std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>>& skinBones,
                     SimilarityTransform previous, std::map<std::string, SimilarityTransform>& out) {
  double scaleSum = 0;
  for (std::size_t b = 0; b < digit.bones.size(); ++b) {
    const auto skin = skinBones.find(digit.skinBones[b]);
    if (skin == skinBones.end()) throw BadInput("", "skeleton placement: no skin bone '" + digit.skinBones[b] + "'");
    MatrixX3d to(2, 3);
    to << skin->second.first.transpose(), skin->second.second.transpose();
    SimilarityTransform t =
        twoPointFit(joints.middleRows(Eigen::Index(b), 2), to, previous.rotation, digit.bones[b]);
    if (b > 0 && b + 1 == digit.bones.size()) {
      // The tip: the skin bone's tail is at the fingertip's skin, past the bone's end, so the last bone
      // takes the mean scale of the digit's other bones and only turns onto the skin bone from its head.
      t.scale = scaleSum / double(b);
      t.translation = to.row(0).transpose() - t.scale * t.rotation * joints.row(Eigen::Index(b)).transpose();
    }
    scaleSum += t.scale;
    previous = t;
    out[digit.bones[b]] = t;
  }
}

}  // namespace

SkeletonCorrespondence rajagopalToMakeHuman() {
  SkeletonCorrespondence c;
  // The atlas's upper facets: the top vertex pair of hat_spine.vtp, (−0.022146, 0.509427, ±0.017856) m
  // in the torso frame; their midpoint in LPS mm.
  c.landmarks.push_back({"atlas", "torso", Eigen::Vector3d(0.0, 22.146, 509.427)});
  // The metacarpophalangeal joints of the index and little fingers: the centroid of the metacarpal's
  // vertices within 10 mm of its end furthest from the wrist (metacarpal2/5_r/lvs.vtp at the model's
  // scale factor 0.85), in the hand frame, LPS mm.
  for (const double side : {1.0, -1.0}) {
    const std::string s = side > 0 ? "_r" : "_l";
    c.landmarks.push_back({"mcp2" + s, "hand" + s, Eigen::Vector3d(-17.145 * side, -4.112, -81.147)});
    c.landmarks.push_back({"mcp5" + s, "hand" + s, Eigen::Vector3d(31.435 * side, 0.499, -67.941)});
  }
  // The digits: Rajagopal's metacarpal 1 and thumb phalanges onto MakeHuman's finger1 bones; metacarpals
  // 2–5 onto MakeHuman's metacarpal1–4, their phalanges onto finger2–5.
  const std::vector<std::string> fingers = {"thumb", "index", "middle", "ring", "little"};
  for (const std::string side : {"r", "l"}) {
    const std::string S = side == "r" ? ".R" : ".L", mesh = "_" + side + "vs";
    c.digits.push_back({"hand_" + side,
                        {"metacarpal1" + mesh, "thumb_proximal" + mesh, "thumb_distal" + mesh},
                        {"finger1-1" + S, "finger1-2" + S, "finger1-3" + S}});
    for (int f = 2; f <= 5; ++f) {
      const std::string finger = fingers[std::size_t(f - 1)], n = std::to_string(f);
      c.digits.push_back({"hand_" + side,
                          {"metacarpal" + n + mesh, finger + "_proximal" + mesh, finger + "_medial" + mesh,
                           finger + "_distal" + mesh},
                          {"metacarpal" + std::to_string(f - 1) + S, "finger" + n + "-1" + S, "finger" + n + "-2" + S,
                           "finger" + n + "-3" + S}});
    }
  }
  c.bodies.push_back(
      {"pelvis", {"femur_r", "femur_l"}, {"upperleg01.R", "upperleg01.L"}, {"femur_r", "femur_l", "torso"}});
  c.bodies.push_back(pairs("torso", {"torso", "humerus_r", "humerus_l", "atlas"},
                           {"spine03", "upperarm01.R", "upperarm01.L", "head-spine"}));
  addSide(c, "r", "R");
  addSide(c, "l", "L");
  return c;
}

std::map<std::string, Eigen::Vector3d> jointPositions(const Skeleton& skeleton) {
  const std::vector<Eigen::Isometry3d> world = skeleton.restWorld();
  std::map<std::string, Eigen::Vector3d> out;
  for (std::size_t j = 0; j < world.size(); ++j) out[skeleton.joints[j].name] = world[j].translation();
  return out;
}

std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>> boneSegments(const Skeleton& skeleton) {
  const std::vector<Eigen::Isometry3d> world = skeleton.restWorld();
  std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>> out;
  for (std::size_t j = 0; j < world.size(); ++j)
    out[skeleton.joints[j].name] = {world[j].translation(), world[j] * skeleton.joints[j].tail};
  return out;
}

SkeletonPlacement placeSkeleton(const Skeleton& model, const SkeletonCorrespondence& correspondence,
                                const std::map<std::string, Eigen::Vector3d>& targets,
                                const Eigen::Matrix3d& skinAxes) {
  const std::vector<Eigen::Isometry3d> world = model.restWorld();
  const PointLookup lookup{model, world, correspondence, targets};
  std::vector<const BodyCorrespondence*> byBody(model.joints.size(), nullptr);
  bool twoPasses = false;
  for (const BodyCorrespondence& c : correspondence.bodies) {
    const int b = model.find(c.body);
    if (b < 0) throw BadInput("", "skeleton placement: no body '" + c.body + "' in the model");
    if (c.modelPoints.size() != c.targetPoints.size())
      throw BadInput("", "skeleton placement: body '" + c.body + "' has unpaired points");
    for (const std::string& other : c.scaleFrom)
      if (model.find(other) < 0) throw BadInput("", "skeleton placement: no body '" + other + "' to take a scale from");
    byBody[std::size_t(b)] = &c;
    twoPasses = twoPasses || !c.scaleFrom.empty();
  }
  SkeletonPlacement out;
  for (int pass = 0; pass < (twoPasses ? 2 : 1); ++pass) {
    SkeletonPlacement next;
    for (std::size_t b = 0; b < model.joints.size(); ++b) {
      const BodyCorrespondence* c = byBody[b];
      const std::size_t n = c ? c->modelPoints.size() : 0;
      const int parent = model.joints[b].parent;
      const SimilarityTransform* placedParent = parent >= 0 ? &next.bodies[std::size_t(parent)] : nullptr;
      MatrixX3d from(n, 3), to(n, 3);
      for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Vector3d x = lookup.modelPoint(c->modelPoints[i]);
        from.row(Eigen::Index(i)) = x.transpose();
        to.row(Eigen::Index(i)) = lookup.target(c->targetPoints[i], x, placedParent, model.joints[b].name).transpose();
      }
      double scale = 0;  // 0: the pairs' own
      if (pass == 1 && !c->scaleFrom.empty()) {
        for (const std::string& other : c->scaleFrom) scale += out.bodies[std::size_t(model.find(other))].scale;
        scale /= double(c->scaleFrom.size());
      }
      next.bodies.push_back(fitBody(from, to, placedParent, skinAxes, model.joints[b].name, scale));
      next.rmsResidual.push_back(n ? std::sqrt((next.bodies.back().apply(from) - to).rowwise().squaredNorm().mean())
                                   : 0.0);
    }
    out = std::move(next);
  }
  return out;
}

MatrixX3d restWorldPoints(const Skeleton& model, int body, const MatrixX3d& local) {
  if (body < 0 || std::size_t(body) >= model.joints.size())
    throw UsageError("restWorldPoints: body " + std::to_string(body) + " is not one of the model's");
  const Eigen::Isometry3d rest = model.restWorld()[std::size_t(body)];
  return (local * rest.linear().transpose()).rowwise() + rest.translation().transpose();
}

MatrixX3d placeBodyPoints(const Skeleton& model, const SkeletonPlacement& placement, int body, const MatrixX3d& local) {
  if (body < 0 || std::size_t(body) >= model.joints.size() || placement.bodies.size() != model.joints.size())
    throw UsageError("placeBodyPoints: body " + std::to_string(body) + " is not one of the placed model's");
  return placement.bodies[std::size_t(body)].apply(restWorldPoints(model, body, local));
}

MatrixX3d digitJoints(const std::vector<MatrixX3d>& bones, const Eigen::Vector3d& base) {
  MatrixX3d joints(Eigen::Index(bones.size() + 1), 3);
  Eigen::Vector3d from = base, distal = base;
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const BoneEnds ends = boneEnds(bones[b], from, b);
    const Eigen::Vector3d joint = b == 0 ? ends.proximal : Eigen::Vector3d(0.5 * (distal + ends.proximal));
    joints.row(Eigen::Index(b)) = joint.transpose();
    distal = ends.distal;
    from = ends.centroid;
  }
  joints.row(joints.rows() - 1) = distal.transpose();
  return joints;
}

std::map<std::string, SimilarityTransform> placeDigits(
    const Skeleton& model, const SkeletonPlacement& placement, const std::vector<DigitCorrespondence>& digits,
    const std::map<std::string, MatrixX3d>& localMeshes,
    const std::map<std::string, std::pair<Eigen::Vector3d, Eigen::Vector3d>>& skinBones) {
  std::map<std::string, SimilarityTransform> out;
  for (const DigitCorrespondence& digit : digits) {
    const int body = model.find(digit.body);
    if (body < 0 || std::size_t(body) >= placement.bodies.size())
      throw BadInput("", "skeleton placement: no placed body '" + digit.body + "' for a digit");
    if (digit.bones.empty() || digit.bones.size() != digit.skinBones.size())
      throw BadInput("", "skeleton placement: a digit of body '" + digit.body + "' has unpaired bones");
    const MatrixX3d joints =
        digitJoints(digitBones(model, body, digit, localMeshes), model.restWorld()[std::size_t(body)].translation());
    placeDigitBones(joints, digit, skinBones, placement.bodies[std::size_t(body)], out);
  }
  return out;
}

std::vector<MatrixX3d> placeMusclePaths(const Skeleton& model, const SkeletonPlacement& placement,
                                        const std::vector<Muscle>& muscles) {
  if (placement.bodies.size() != model.joints.size())
    throw UsageError("placeMusclePaths: the placement is not of this model");
  const std::vector<Eigen::Isometry3d> world = model.restWorld();
  std::vector<MatrixX3d> paths;
  for (const Muscle& muscle : muscles) {
    MatrixX3d path(Eigen::Index(muscle.path.size()), 3);
    for (std::size_t i = 0; i < muscle.path.size(); ++i) {
      const PathPoint& p = muscle.path[i];
      if (p.body < 0 || std::size_t(p.body) >= model.joints.size())
        throw UsageError("placeMusclePaths: point '" + p.name + "' of muscle '" + muscle.name + "' is not on a body");
      path.row(Eigen::Index(i)) = placement.bodies[std::size_t(p.body)]
                                      .apply(Eigen::Vector3d(world[std::size_t(p.body)] * p.location))
                                      .transpose();
    }
    paths.push_back(std::move(path));
  }
  return paths;
}

}  // namespace vesalius::transfer
