// vesalius rig: the posing rig of a body (Sujar et al. 2018, §3.1-3.5 preprocessing) from a skin and a skeleton, from
// a label map with segmented bones, or from a reference anatomy with OpenSim's bone meshes placed in its
// skin (rigging/body_rig.h), written as a rig folder with the meshes it will carry (io/anatomy_rig_io.h).
#include "command_runner.h"
#include "common.h"
#include "label_map_input.h"

#include "vesalius/core/error.h"
#include "vesalius/io/anatomy_rig_io.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/io/skeleton_io.h"
#include "vesalius/rigging/body_rig.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct RigOptions {
  std::string skin, skeleton, baseMesh, out, space = "auto", labels, grid, labelTable, reference;
  posing::SkeletonFromBonesOptions bones;
  // With the femurs placed on the pelvis's hip centres (skeleton_placement.h), the default 6 mm finds 20
  // (right) and 70 (left) femoral head vertices, centres 1.6 and 0.8 mm from the placed femurs' own.
  posing::SkeletonFromBoneMeshesOptions meshBones;
  double acetabulumDistance = NAN;  // --acetabulum-distance if given, for bones or meshBones
  std::vector<std::string> tissues;
  rigging::RigOptions rig;
  CommonOptions common;
};

// MakeHuman's space (decimetres, +Y up, facing +Z) to ours (mm, LPS); the identity for "lps".
TriMesh toLps(TriMesh mesh, bool makeHuman) {
  if (makeHuman) mesh.V = io::transformPoints(mesh.V, io::yUpToLps(), 100.0);
  return mesh;
}

// skin: as read (a MakeHuman body in base.obj's units), for placing a .mhskel's joints in it.
Skeleton readSkeleton(const RigOptions& o, const TriMesh& skin, bool makeHuman) {
  if (fileExtension(o.skeleton) == ".bvh") {
    const Skeleton s = io::readBvh(o.skeleton, std::cerr).skeleton;
    return makeHuman ? io::transformSkeleton(s, io::yUpToLps(), 100.0) : s;
  }
  if (fileExtension(o.skeleton) != ".mhskel") throw UsageError("rig: --skeleton must be a .mhskel or .bvh file");
  const std::string base = o.baseMesh.empty() ? (fs::path(o.skeleton).parent_path() / "base.obj").string() : o.baseMesh;
  if (!fs::exists(base)) throw UsageError(o.skeleton + ": a MakeHuman skeleton needs its base mesh; pass --base-mesh");
  const Skeleton s = io::readMakeHumanSkeletonOfBody(o.skeleton, io::readTriMesh(base), skin);
  return makeHuman ? io::transformSkeleton(s, io::yUpToLps(), 100.0) : s;
}

// `meshes` and every --tissue, in the rig's space (a MakeHuman tissue converted as its skin is).
std::vector<std::pair<std::string, TriMesh>> withTissues(const RigOptions& o, std::vector<std::pair<std::string, TriMesh>> meshes,
                                                         bool makeHuman = false) {
  for (const std::string& t : o.tissues) meshes.emplace_back(fs::path(t).filename().string(), toLps(io::readTriMesh(t), makeHuman));
  return meshes;
}

// Writes the rig with `meshes` and reports what was built.
void finishRig(const RigOptions& o, rigging::BuiltRig& built, std::vector<std::pair<std::string, TriMesh>> meshes,
               io::Report& report) {
  for (const auto& [stage, seconds] : built.stageSeconds) report.stage(stage, seconds);
  std::vector<std::string> names;
  for (const auto& [name, mesh] : meshes) names.push_back(name);
  built.rig.meshJoint = rigging::meshJoints(names, built.boneJoints);
  const AnatomyRig& rig = built.rig;
  io::writeAnatomyRig(o.out, rig, meshes, o.common.writeOptions());
  report.output("anatomy", o.out);
  const Eigen::VectorXi& bone = rig.boneOfVertex();
  const long boneVertices = (bone.array() >= 0).count();
  report.metric("tet_vertices", rig.tets.V.rows());
  report.metric("tets", rig.tets.T.rows());
  report.metric("bones", rig.boneJoint.size());
  report.metric("bone_meshes", std::count_if(rig.meshJoint.begin(), rig.meshJoint.end(), [](int j) { return j >= 0; }));
  report.metric("bone_vertices", boneVertices);
  if (!std::isnan(built.femoralHeadRadiusLeft)) {
    report.metric("femoral_head_radius_left_mm", built.femoralHeadRadiusLeft);
    report.metric("femoral_head_radius_right_mm", built.femoralHeadRadiusRight);
  }
  std::cout << o.out << ": " << rig.tets.V.rows() << " vertices, " << rig.tets.T.rows() << " tets, "
            << rig.boneJoint.size() << " of " << rig.skeleton.joints.size() << " joints with bone regions ("
            << boneVertices << " bone vertices), " << meshes.size() << " mesh(es)\n";
  warnIfOverTetTarget(long(rig.tets.T.rows()), o.rig.targetTets, "--target-tets");
}

void reportParameters(const RigOptions& o, io::Report& report) {
  report.parameter("voxel_size_mm", o.rig.voxelSize);
  report.parameter("target_tets", o.rig.targetTets);
  report.parameter("cor_centres", o.rig.corCentres);
}

void runSkinRig(const RigOptions& o, CommandRun& run) {
  if (o.space != "auto" && o.space != "makehuman" && o.space != "lps")
    throw UsageError("rig: --space must be auto, makehuman or lps");
  const bool makeHuman = o.space == "makehuman" || (o.space == "auto" && fileExtension(o.skeleton) == ".mhskel");
  run.report.input("skin", o.skin);
  run.report.input("skeleton", o.skeleton);
  reportParameters(o, run.report);
  run.report.parameter("capsule_radius_fraction", o.rig.capsules.radiusFraction);
  run.report.parameter("capsule_end_trim", o.rig.capsules.endTrim);
  const TriMesh asRead = io::readTriMesh(o.skin);
  const Skeleton skeleton = readSkeleton(o, asRead, makeHuman);
  const TriMesh skin = toLps(asRead, makeHuman);
  rigging::BuiltRig built = rigging::rigFromSkeleton(skin, skeleton, o.rig, o.skin, o.skeleton, &run.progress);
  finishRig(o, built, withTissues(o, {{"skin" + fileExtension(o.skin), skin}}, makeHuman), run.report);
}

void runLabelRig(const RigOptions& o, CommandRun& run) {
  run.report.input("labels", o.labels);
  reportParameters(o, run.report);
  run.report.parameter("margin_mm", o.rig.margin);
  const LabelMap map = readLabelsOption(o.labels, o.labelTable, o.grid, run.report);
  posing::SkeletonFromBonesOptions bones = o.bones;
  if (!std::isnan(o.acetabulumDistance)) bones.acetabulumDistance = o.acetabulumDistance;
  rigging::BuiltRig built = rigging::rigFromBoneLabels(map, bones, o.rig, o.labels, &run.progress);
  finishRig(o, built, withTissues(o, std::move(built.regionSurfaces)), run.report);
}

void runReferenceRig(const RigOptions& o, CommandRun& run) {
  run.report.input("reference", o.reference);
  reportParameters(o, run.report);
  const ReferenceAnatomy reference = io::readReferenceAnatomy(o.reference);
  posing::SkeletonFromBoneMeshesOptions bones = o.meshBones;
  if (!std::isnan(o.acetabulumDistance)) bones.acetabulumDistance = o.acetabulumDistance;
  rigging::BuiltRig built = rigging::rigFromReference(reference, bones, o.rig, o.reference, &run.progress);
  std::vector<std::pair<std::string, TriMesh>> meshes{{"skin.obj", reference.skin}};
  for (const ReferenceTissue& t : reference.tissues) meshes.emplace_back(t.name + ".obj", t.mesh);
  finishRig(o, built, withTissues(o, std::move(meshes)), run.report);
}

void runRig(const RigOptions& o, CommandRun& run) {
  const bool fromSkin = !o.skin.empty() || !o.skeleton.empty();
  if (int(fromSkin) + int(!o.labels.empty()) + int(!o.reference.empty()) != 1)
    throw UsageError("rig: give --skin and --skeleton, or --labels, or --reference (one of them)");
  if (fromSkin && (o.skin.empty() || o.skeleton.empty())) throw UsageError("rig: --skin and --skeleton go together");
  if (!o.labelTable.empty() && o.labels.empty()) throw UsageError("rig: --label-table needs --labels");
  // The rig folder is written whole at the end (io/anatomy_rig_io.h); its path is checked before the work.
  checkOutputFolder(o.out, o.common.writeOptions());
  if (!o.reference.empty()) return runReferenceRig(o, run);
  fromSkin ? runSkinRig(o, run) : runLabelRig(o, run);
}

}  // namespace

void addRigCommand(CLI::App& app) {
  auto o = std::make_shared<RigOptions>();
  CLI::App* cmd = app.add_subcommand("rig", "Posing rig of a body: tet mesh, bone regions, weights, CoR centres");
  cmd->add_option("--skin", o->skin, "Closed body surface (.obj .stl .vtp .ply .vtk), with --skeleton");
  cmd->add_option("--skeleton", o->skeleton, "Skeleton: MakeHuman .mhskel or .bvh, with --skin");
  addLabelsOption(*cmd, o->labels, o->grid,
                  "Instead of --skin/--skeleton: a label map with segmented bones (hip_left, hip_right, sacrum, "
                  "femur_left, femur_right, vertebrae_L5 upward); skeleton and bone regions from its labels");
  cmd->add_option("--label-table", o->labelTable, "Label table for --labels (default: the one beside it)");
  cmd->add_option("--reference", o->reference,
                  "Instead of --skin/--skeleton or --labels: a reference anatomy with OpenSim's bone meshes in its "
                  "skin (`reference full-body`); skeleton (pelvis, legs, torso, arms) and bone regions from the meshes");
  cmd->add_option("--acetabulum-distance", o->acetabulumDistance,
                  "With --labels or --reference: femoral head voxels or vertices within this of the hip bone give the "
                  "hip centre, mm (default 6)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--base-mesh", o->baseMesh, "MakeHuman base.obj for a .mhskel (default: beside it)");
  cmd->add_option("--tissue", o->tissues, "A mesh to carry along (organ, bone, muscle), repeatable");
  cmd->add_option("--space", o->space,
                  "Space of the inputs: makehuman (decimetres, +Y up; converted to mm LPS), lps (mm), or auto "
                  "(makehuman for a .mhskel)")
      ->capture_default_str();
  cmd->add_option("--margin", o->rig.margin, "With --labels: mesh the bones' bounding box grown by this, mm")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--voxel-size", o->rig.voxelSize, "Voxel size of the inside image (--skin, --reference) or of the labels meshed (--labels; coarser only), mm (grown to keep it under "
                                               "250x120x700 voxels, Sujar et al. 2018, §3.2)")
      ->capture_default_str();
  cmd->add_option("--target-tets", o->rig.targetTets, "About this many tets")->capture_default_str();
  cmd->add_option("--capsule-radius", o->rig.capsules.radiusFraction,
                  "Bone capsule radius as a fraction of the bone's distance to the skin")
      ->capture_default_str();
  cmd->add_option("--capsule-trim", o->rig.capsules.endTrim, "Fraction of each bone left free at both ends")
      ->capture_default_str();
  cmd->add_flag("--cor-centres,!--no-cor-centres", o->rig.corCentres,
                "Compute the centres of rotation that `pose --method cor` needs (default; a few seconds for the "
                "body's 50 bones); --no-cor-centres skips them");
  cmd->add_option("--out", o->out, "Anatomy directory to write (rig.vtu, bones.txt, skeleton.bvh, meshes/)")->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example (with the centres of rotation for `pose --method cor`; add --no-cor-centres to skip them):\n"
      "  vesalius rig --skin testdata/body/shapes/mh_neutral_body.obj "
      "--skeleton testdata/body/default.mhskel --out body-rig\n"
      "Bones are capsules around the skeleton's segments (no bone meshes are needed); a MakeHuman body of any shape\n"
      "gets its own joints; see docs/methods/posing.md.\n"
      "From a CT's bone labels (TotalSegmentator names; the pelvis, femurs and lumbar spine):\n"
      "  vesalius rig --labels seg.nii.gz --label-table labels_total_v1.tsv --target-tets 20000 --out ct-rig\n"
      "From the full-body reference (OpenSim's bones in MakeHuman's skin; joints pelvis, femur_l, tibia_l, talus_l, ...):\n"
      "  vesalius rig --reference body-reference --voxel-size 6 --target-tets 20000 --out body-bones-rig\n"
      "(coarser voxels and fewer tets rig faster; the defaults make about 100k tets)");
  cmd->callback([o] { runCommand("rig", o->common, [&](CommandRun& run) { runRig(*o, run); }); });
}

}  // namespace vesalius::cli
