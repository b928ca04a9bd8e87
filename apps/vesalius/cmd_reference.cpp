// vesalius reference torso: a reference anatomy for anatomy transfer (seed 000 §3, Fig. 2.c) built from a
// labelled CT: the body's surface as the skin, every label of the segmentation as a bone, muscle or organ.
#include "body_distance.h"
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/makehuman_uv.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/skeleton_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/patient/scan_anatomy.h"
#include "vesalius/transfer/anatomy_checks.h"
#include "vesalius/transfer/body_frame.h"
#include "vesalius/transfer/bones_inside_skin.h"
#include "vesalius/transfer/bones_warped_into_skin.h"
#include "vesalius/transfer/skeleton_placement.h"

#include <Eigen/Geometry>

#include <filesystem>

#include <iostream>
#include <map>
#include <memory>

namespace vesalius::cli {

namespace {

struct ReferenceOptions {
  std::string scan, labels, table, out, name;
  int skinFaces = 20000, tissueFaces = 3000;
  CommonOptions common;
};

struct FullBodyOptions {
  std::string skin, skeleton, baseMesh, model, out;
  CommonOptions common;
};

void runReference(const ReferenceOptions& o) {
  io::Report report("reference torso");
  report.input("scan", o.scan);
  report.input("labels", o.labels);
  report.parameter("skin_faces", o.skinFaces);
  report.parameter("tissue_faces", o.tissueFaces);
  Progress progress(o.common.progressStyle());
  const Image ct = io::readScan(o.scan);
  const LabelMap labels = io::readLabelMap(o.labels, o.table);
  patient::ScanAnatomyOptions surfaces;
  surfaces.skinFaces = o.skinFaces;
  surfaces.tissueFaces = o.tissueFaces;
  ReferenceAnatomy anatomy;
  {
    auto timer = report.time("skin and tissues");
    anatomy = patient::scanAnatomy(ct, labels, surfaces, o.scan, o.labels, &progress);
  }
  anatomy.name = o.name.empty() ? "torso (" + o.scan + ")" : o.name;
  io::writeReferenceAnatomy(o.out, anatomy, o.common.writeOptions());
  report.output("reference", o.out);
  int bones = 0;
  for (const ReferenceTissue& t : anatomy.tissues) bones += t.kind == TissueKind::Bone;
  report.metric("tissues", anatomy.tissues.size());
  report.metric("bones", bones);
  report.metric("skin_vertices", anatomy.skin.V.rows());
  report.metric("skin_cut_vertices", anatomy.skinCutVertices.size());
  std::cout << o.out << ": skin of " << anatomy.skin.V.rows() << " vertices (" << anatomy.skinCutVertices.size()
            << " on the field of view's cut), " << anatomy.tissues.size()
            << " tissues (" << bones << " bones), sagittal normal " << anatomy.sagittal.normal.transpose() << "\n";
  o.common.finish(report);
}

// OpenSim bodies of the trunk (seed 000 §8: skull, spine, sternum, pelvis, rib cage move symmetrically).
bool isTrunkBody(const std::string& body) { return body == "pelvis" || body == "torso"; }

// A bone mesh's group (the bones that move by one map in §8): its OpenSim body, but for the skull and jaw,
// which Rajagopal's torso carries with the spine and rib cage: §8 gives each trunk bone a map of its own,
// and one trunk map scaled the skull with a muscular body's chest (determinant 1.9) into its face.
std::string boneGroup(const std::string& body, const std::string& mesh) {
  return body == "torso" && (mesh == "hat_skull" || mesh == "hat_jaw") ? io::kSkullGroup : body;
}

// Signed distances to a closed skin (transfer::SkinDistanceFunction): distance and outward direction from
// the closest point on it, the side from the signed distance field the transfer report's rules R5, R6
// use (body_distance.h).
transfer::SkinDistanceFunction skinDistances(const TriMesh& skin) {
  const auto field = std::make_shared<const Grid<float>>(bodySignedDistance(skin).signedDistance);
  const auto tree = std::make_shared<const TriangleTree>(skin.V, skin.F);
  return [field, tree](const MatrixX3d& P) {
    const std::vector<ClosestPoint> closest = tree->closest(P);
    const Eigen::VectorXd sampled = transfer::sampleSignedDistance(*field, P, kDistanceBandMm);
    transfer::SkinDistances d{Eigen::VectorXd(P.rows()), MatrixX3d::Zero(P.rows(), 3)};
    for (Eigen::Index r = 0; r < P.rows(); ++r) {
      const double side = sampled[r] < 0 ? -1.0 : 1.0;
      const Eigen::Vector3d away = P.row(r).transpose() - closest[std::size_t(r)].point;
      d.distance[r] = side * away.norm();
      if (away.norm() > 1e-9) d.outward.row(r) = side * away.normalized().transpose();
    }
    return d;
  };
}

// The bones that move inside the skin together (moveBonesInsideSkin), by name: a trunk group (symmetric,
// seed 000 §8) as one, every other bone mesh alone (the hand's carpals apart from its digits, which the
// placement already fits bone by bone). Each tissue's unit name is in unitOfTissue. The skull and jaw
// (one symmetric unit) need the skin's mouth counted as inside (body_distance.h): 2,031 of their vertices
// lie in it, which no similarity of the skull leaves (docs/methods/skeleton-alignment.md).
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

// Rule R6 for the reference itself: each unit of bones (unitsIntoSkin) moved inside the skin by the
// smallest similarity change (bones_inside_skin.h; the trunk's groups kept symmetric about the sagittal
// plane) that keeps the joints near it (`joints`, the placed joint centres) in place, the points fixed to
// its bones with it, and what is still outside then bent inside (bones_warped_into_skin.h). Reports each
// unit's change and the bone vertices outside the skin before, after the change and after the bend.
void moveBonesInsideSkin(ReferenceAnatomy& anatomy, const MatrixX3d& joints, io::Report& report) {
  const transfer::SkinDistanceFunction skin = skinDistances(anatomy.skin);
  std::map<std::string, std::string> unitOfTissue;
  long before = 0, after = 0;
  nlohmann::json changes;
  for (const auto& [unit, members] : unitsIntoSkin(anatomy, unitOfTissue)) {
    const MatrixX3d V = stackedVertices(anatomy, members), near = jointsOfBones(V, joints);
    const transfer::InsideSkinCorrection c =
        transfer::correctionIntoSkin(V, near, skin,
                                     anatomy.tissues[members[0]].symmetric ? &anatomy.sagittal : nullptr);
    const transfer::InsideSkinWarp bend = transfer::warpIntoSkin(c.change.apply(V), skin);
    for (const std::size_t t : members) anatomy.tissues[t].mesh.V = bend.apply(c.change.apply(anatomy.tissues[t].mesh.V));
    for (ReferencePoint& p : anatomy.points)
      if (unitOfTissue.count(p.tissue) && unitOfTissue.at(p.tissue) == unit)
        p.position = bend.apply(c.change.apply(p.position).transpose()).transpose();
    const Eigen::Vector3d centroid = V.colwise().mean().transpose();
    changes[unit] = {{"outside_before", c.outsideBefore}, {"outside_after_change", c.outsideAfter},
                     {"outside_after", bend.outsideAfter}, {"bend_largest_mm", bend.largestMoveMm},
                     {"scale", c.change.scale},
                     {"turn_degrees", Eigen::AngleAxisd(c.change.rotation).angle() * 180.0 / M_PI},
                     {"centroid_shift_mm", (c.change.apply(centroid) - centroid).norm()},
                     {"joints", near.rows()},
                     {"joint_shift_mm", near.rows() ? (c.change.apply(near) - near).rowwise().norm().maxCoeff() : 0.0}};
    before += c.outsideBefore;
    after += bend.outsideAfter;
  }
  report.metric("bones_into_skin", changes);
  report.metric("bone_vertices_outside_skin_before", before);
  report.metric("bone_vertices_outside_skin", after);
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

// The full-body reference (seed 000 §3): the MakeHuman skin with the OpenSim model's bones and muscle
// path points placed inside it by seed 004's body frame and per-body similarity fits (skeleton_placement.h).
// Each bone mesh is a tissue; the meshes of one OpenSim body form one bone group (boneGroup: the skull
// apart); path points are fixed to their body's first mesh.
void runFullBody(const FullBodyOptions& o) {
  io::Report report("reference full-body");
  report.input("skin", o.skin);
  report.input("skeleton", o.skeleton);
  report.input("model", o.model);
  namespace fs = std::filesystem;
  const std::string base = o.baseMesh.empty() ? (fs::path(o.skeleton).parent_path() / "base.obj").string() : o.baseMesh;
  ReferenceAnatomy anatomy;
  anatomy.name = "full body (" + fs::path(o.skin).filename().string() + ", " + fs::path(o.model).filename().string() + ")";
  const TriMesh baseMesh = io::readTriMesh(base);
  anatomy.skin = io::readTriMesh(o.skin);
  if (anatomy.skin.UV.rows() == 0) anatomy.skin = io::withMakeHumanUv(std::move(anatomy.skin), baseMesh, base);
  anatomy.skin.V = io::transformPoints(anatomy.skin.V, io::yUpToLps(), 100.0);
  const Skeleton rig = io::transformSkeleton(io::readMakeHumanSkeleton(o.skeleton, baseMesh.V), io::yUpToLps(), 100.0);
  std::map<std::string, Eigen::Vector3d> joints = transfer::jointPositions(rig);
  for (const char* name : {"upperleg01.L", "foot.L", "upperleg01.R", "foot.R"})
    if (!joints.count(name)) throw BadInput(o.skeleton, std::string("no joint '") + name + "' (a MakeHuman default rig is needed)");
  const transfer::BodyFrame frame = transfer::computeBodyFrame(
      anatomy.skin.V, anatomy.skin.F, {joints.at("upperleg01.L"), joints.at("foot.L"), joints.at("upperleg01.R"), joints.at("foot.R")});
  joints["head-spine"] = frame.headSpineJoint;
  anatomy.sagittal = {frame.sagittalPoint, frame.sagittalNormal};

  MusculoskeletalModel model = io::readOpenSimModel(o.model);
  model.bodies = io::transformSkeleton(model.bodies, io::openSimToLps(), 1000.0);
  for (Muscle& m : model.muscles)
    for (PathPoint& point : m.path) point.location = 1000.0 * io::openSimToLps() * point.location;
  const transfer::SkeletonCorrespondence correspondence = transfer::rajagopalToMakeHuman();
  const transfer::SkeletonPlacement placement =
      transfer::placeSkeleton(model.bodies, correspondence, joints, frame.axes());
  const fs::path geometryDir = fs::path(o.model).parent_path() / "Geometry";
  std::vector<TriMesh> meshes;  // per geometry entry, vertices in its body's frame (LPS mm)
  std::map<std::string, MatrixX3d> localMeshes;
  for (const AttachedGeometry& g : model.geometry) {
    meshes.push_back(io::readTriMesh((geometryDir / g.meshFile).string()));
    meshes.back().V = io::transformPoints(meshes.back().V * g.scale.asDiagonal(), io::openSimToLps(), 1000.0);
    localMeshes[fs::path(g.meshFile).stem().string()] = meshes.back().V;
  }
  const std::map<std::string, fit::SimilarityTransform> digits =
      transfer::placeDigits(model.bodies, placement, correspondence.digits, localMeshes, transfer::boneSegments(rig));
  // Points of a body's frame (#P by 3) placed as its mesh `name` is: by the body's placement, or by the
  // digit's own fit.
  const auto placeAsMesh = [&](const std::string& name, int body, const MatrixX3d& local) {
    const auto digit = digits.find(name);
    return digit == digits.end() ? transfer::placeBodyPoints(model.bodies, placement, body, local)
                                 : digit->second.apply(transfer::restWorldPoints(model.bodies, body, local));
  };
  std::map<int, std::string> firstTissueOfBody;
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const AttachedGeometry& g = model.geometry[m];
    const std::string name = fs::path(g.meshFile).stem().string(), body = model.bodies.joints[g.body].name;
    TriMesh mesh = std::move(meshes[m]);
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
  // The joint centres, which the transfer carries too (seed 000 §8): each non-root body's origin, named
  // joint/BODY and fixed to the body's first mesh.
  for (std::size_t b = 0; b < model.bodies.joints.size(); ++b) {
    if (model.bodies.joints[b].parent < 0) continue;
    const auto first = firstTissueOfBody.find(int(b));
    const std::string tissue = first == firstTissueOfBody.end() ? "" : first->second;
    anatomy.points.push_back({"joint/" + model.bodies.joints[b].name, tissue,
                              placeAsMesh(tissue, int(b), MatrixX3d::Zero(1, 3)).row(0).transpose()});
  }
  moveBonesInsideSkin(anatomy, placedJoints(model.bodies, placement), report);
  io::writeReferenceAnatomy(o.out, anatomy, o.common.writeOptions());
  report.output("reference", o.out);
  report.metric("bones", anatomy.tissues.size());
  report.metric("points", anatomy.points.size());
  report.metric("head_slices", frame.headSlices);
  std::cout << o.out << ": skin of " << anatomy.skin.V.rows() << " vertices, " << anatomy.tissues.size() << " bone meshes, "
            << anatomy.points.size() << " points (muscle paths and joint centres)\n";
  o.common.finish(report);
}

}  // namespace

void addReferenceCommand(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand("reference", "Build a reference anatomy for `vesalius transfer`");
  cmd->require_subcommand(1);
  CLI::App* torso = cmd->add_subcommand("torso", "Reference anatomy from a labelled CT: body surface as skin, every label as a tissue");
  torso->add_option("--scan", o->scan, "The CT (NIfTI, NRRD, MetaImage, DICOM folder)")->required();
  torso->add_option("--labels", o->labels, "Its label map (TotalSegmentator names: bones, muscles, organs)")->required();
  torso->add_option("--label-table", o->table, "Label table (TSV or Slicer .ctbl) naming the labels");
  torso->add_option("--name", o->name, "Name stored in reference.json");
  torso->add_option("--skin-faces", o->skinFaces, "Triangles of the skin surface")->capture_default_str();
  torso->add_option("--tissue-faces", o->tissueFaces, "Triangles of each tissue surface")->capture_default_str();
  torso->add_option("--out", o->out, "Reference folder to write (reference.json, skin.obj, tissues/)")->required();
  addCommonOptions(*torso, o->common);
  torso->footer(
      "Example:\n  vesalius reference torso --scan testdata/ct-abdomen-pelvis/example_ct.nii.gz \\\n"
      "    --labels testdata/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz \\\n"
      "    --label-table testdata/ct-abdomen-pelvis/labels_total_v1.tsv --out torso-reference\n"
      "Trunk bones (vertebrae, pelvis, rib cage) are marked symmetric; see docs/methods/anatomy-transfer.md.");
  torso->callback([o] { runReference(*o); });

  auto f = std::make_shared<FullBodyOptions>();
  CLI::App* full = cmd->add_subcommand("full-body", "Reference anatomy from a MakeHuman skin with an OpenSim skeleton placed inside it");
  full->add_option("--skin", f->skin, "MakeHuman body (.obj, decimetres, +Y up)")->required();
  full->add_option("--skeleton", f->skeleton, "MakeHuman default rig (.mhskel)")->required();
  full->add_option("--base-mesh", f->baseMesh, "MakeHuman base.obj for the rig, and the uv of a skin without them (default: beside the rig)");
  full->add_option("--model", f->model, "OpenSim model (.osim) with its Geometry folder beside it")->required();
  full->add_option("--out", f->out, "Reference folder to write")->required();
  addCommonOptions(*full, f->common);
  full->footer(
      "Example:\n  vesalius reference full-body --skin testdata/body/shapes/mh_neutral_body.obj \\\n"
      "    --skeleton testdata/body/default.mhskel --model testdata/skeleton-opensim/Rajagopal2016.osim --out body-reference\n"
      "The skeleton is placed by seed 004's body frame and per-bone similarity fits; see docs/methods/skeleton-alignment.md.");
  full->callback([f] { runFullBody(*f); });
}

}  // namespace vesalius::cli
