// vesalius patient: one patient's CT (and its organ/bone segmentation) in, that patient's anatomy out
// (patient/virtual_patient.h). Reads the inputs and the organ template library, runs the pipeline, writes
// the output folder whole or not at all. vesalius demo is the same command on the shipped CT and labels.
#include "common.h"
#include "full_body_sources.h"
#include "posing_session.h"

#include "vesalius/core/error.h"
#include "vesalius/core/markers.h"
#include "vesalius/io/anatomy_rig_io.h"
#include "vesalius/io/gltf.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/patient/virtual_patient.h"
#include "vesalius/posing/joint_angles.h"
#include "vesalius/posing/rig_poser.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"
#include "vesalius/viz/slice_overlay.h"
#include "vesalius/viz/surface_render.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct PatientOptions {
  std::string scan, organs, organTable, out, templates = VESALIUS_TEMPLATE_DIR "/organs";
  std::string pose, motion;  // joint angles, or a BVH motion and its frame
  int frame = 0;
  std::string reference;     // a full-body reference folder; empty: built from the shipped sources
  bool complete = true;      // complete the full-body reference into the patient
  bool png = false;
  long rigTets = 0;        // 0: the rig's own default
  double rigVoxelSize = 0;  // 0: the rig's own default
  patient::VirtualPatientOptions pipeline;
  patient::PatientPoseOptions posing;
  CommonOptions common;
};

// Every <organ>.obj (.stl .ply .vtp) of the library folder, the organ named by the file's stem.
std::vector<patient::OrganTemplate> readTemplates(const std::string& folder) {
  if (!fs::is_directory(folder)) throw BadInput(folder, "no such template folder");
  std::vector<patient::OrganTemplate> templates;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string ext = fileExtension(e.path().string());
    if (!e.is_regular_file() || (ext != ".obj" && ext != ".stl" && ext != ".ply" && ext != ".vtp")) continue;
    templates.push_back({e.path().stem().string(), io::readTriMesh(e.path().string()), e.path().string()});
  }
  std::sort(templates.begin(), templates.end(), [](const auto& a, const auto& b) { return a.organ < b.organ; });
  return templates;
}

nlohmann::json fitReport(const patient::FittedOrgan& f) {
  const auto meanAndMax = [](const Eigen::VectorXd& e) {
    return nlohmann::json{{"mean", e.mean()}, {"max", e.maxCoeff()}};
  };
  return {{"template", f.templateSource},
          {"markers", f.fit.markers.rows()},
          {"error_before_mm", meanAndMax(f.fit.errorBefore)},
          {"error_after_mm", meanAndMax(f.fit.errorAfter)},
          {"tets_per_round", f.fit.tetsPerRound},
          {"mean_error_per_round_mm", f.fit.meanErrorPerRound}};
}

MarkerSet icpMarkers(const patient::FittedOrgan& f) {
  MarkerSet set;
  set.name = f.organ;
  for (Eigen::Index i = 0; i < f.fit.markers.rows(); ++i) {
    Marker m;
    m.label = "icp-" + std::to_string(i + 1);
    m.kind = MarkerKind::IcpMarker;
    m.position = f.fit.markers.row(i).transpose();
    m.description = "on label " + f.organ;
    set.markers.push_back(std::move(m));
  }
  return set;
}

void renderPng(const ReferenceAnatomy& anatomy, const std::string& path) {
  std::vector<viz::SurfaceLayer> layers;
  for (const ReferenceTissue& t : anatomy.tissues) layers.push_back({&t.mesh, tissueKindColour(t.kind), 1.0});
  layers.push_back({&anatomy.skin, kSkinColour, 0.2});
  viz::writeSurfacesPng(layers, path, {});
}

// The whole model inside its translucent skin, the scan's own skin over it: where the patient ends and the
// reference goes on.
void renderCompletionPng(const ReferenceAnatomy& whole, const ReferenceAnatomy& scan, const std::string& path) {
  std::vector<viz::SurfaceLayer> layers;
  for (const ReferenceTissue& t : whole.tissues) layers.push_back({&t.mesh, tissueKindColour(t.kind), 1.0});
  layers.push_back({&whole.skin, kSkinColour, 0.15});
  layers.push_back({&scan.skin, viz::Rgb{{90, 160, 230}}, 0.35});
  viz::writeSurfacesPng(layers, path, {});
}

// The anatomy with the posed vertices of the rig's meshes (skin first, then the tissues in order).
ReferenceAnatomy posedAnatomy(const ReferenceAnatomy& rest, const patient::PosedPatient& posed) {
  ReferenceAnatomy anatomy = rest;
  anatomy.skin.V = posed.meshes[0];
  for (std::size_t t = 0; t < anatomy.tissues.size(); ++t) anatomy.tissues[t].mesh.V = posed.meshes[t + 1];
  return anatomy;
}

nlohmann::json qualityReport(const patient::PosedPatient& posed) {
  const posing::PoseQuality& q = posed.quality;
  return {{"inverted_tets", q.inverted},
          {"min_tet_volume_ratio", q.minVolumeRatio},
          {"skin_volume_change_pct", q.skinVolumeChangePct},
          {"tet_volume_change_pct", q.tetVolumeChangePct},
          {"tissue_vertices_left_outside", q.leftOutside},
          {"tissue_vertices_inside_at_rest", posed.tissueVerticesInsideAtRest},
          {"untangled_tets", q.untangle.badBefore},
          {"restore_max_move_mm", q.restore.maxMove}};
}

// DIR/posed/: the posed model (anatomy/ and patient.glb), the rig's posed tets and skeleton, the scan and
// organ map re-posed.
void writePosed(const PatientOptions& o, const patient::VirtualPatient& p, const patient::PosedPatient& posed,
                const std::vector<Eigen::Isometry3d>& world, const std::string& dir, io::Report& report) {
  fs::create_directories(dir);
  const ReferenceAnatomy anatomy = posedAnatomy(p.model(), posed);
  io::writeReferenceAnatomy(dir + "/anatomy", anatomy, {});
  io::writeAnatomyGlb(dir + "/patient.glb", anatomy, {});
  TetMesh tets = p.rig->rig.tets;
  tets.V = posed.tets;
  io::writeTetMesh(dir + "/tets.vtu", tets);
  io::writeBvh(dir + "/skeleton.bvh", io::posedSkeletonMotion(p.rig->rig.skeleton, world), {});
  io::writeScan(dir + "/scan.nii.gz", posed.scan, {});
  if (posed.organs) io::writeLabelMap(dir + "/organs.nii.gz", *posed.organs, {});
  if (o.png) renderPng(anatomy, dir + "/patient.png");
  nlohmann::json pose = qualityReport(posed);
  pose["method"] = o.posing.method;
  if (!o.pose.empty()) pose["angles"] = o.pose;
  if (!o.motion.empty()) pose["motion"] = {{"file", o.motion}, {"frame", o.frame}};
  report.metric("pose", pose);
}

// --pose's syntax and joint names, before the work: the whole model's rig has OpenSim's bodies
// (posing/skeleton_from_bone_meshes.h); without the reference, the rig has the pelvis, the femurs and the
// lumbar vertebrae of the organ map (posing/skeleton_from_bones.h).
void checkPoseJoints(const PatientOptions& o) {
  const posing::SkeletonFromBonesOptions& bones = o.pipeline.rigging.bones;
  std::vector<std::string> joints{"pelvis", bones.femurLeft, bones.femurRight};
  joints.insert(joints.end(), bones.spine.begin(), bones.spine.end());
  if (o.complete) joints = posing::meshSkeletonJoints();
  for (const posing::JointAngle& a : posing::parseJointAngles(o.pose))
    if (std::find(joints.begin(), joints.end(), a.joint) == joints.end()) {
      std::string list;
      for (const std::string& j : joints) list += (list.empty() ? "" : ", ") + j;
      throw UsageError("patient: --pose: no joint '" + a.joint + "' in the patient's rig (" + list + ")");
    }
}

// The full-body reference to complete into the patient: --reference's folder, or built from the shipped
// MakeHuman body and OpenSim model as `vesalius reference full-body` builds it by default.
ReferenceAnatomy fullBodyReference(const PatientOptions& o) {
  if (!o.reference.empty()) return io::readReferenceAnatomy(o.reference);
  const std::string skeleton = VESALIUS_DATA_DIR "/body/default.mhskel";
  const patient::FullBodySources sources =
      readFullBodySources(VESALIUS_DATA_DIR "/body/shapes/mh_neutral_body.obj", skeleton, "",
                          VESALIUS_DATA_DIR "/skeleton-opensim/Rajagopal2016.osim");
  return patient::buildFullBodyReference(sources, skeleton).anatomy;
}

// The completed skin with the fat and the vertices the scan's skin pulled; how the reference's bones met
// the patient's labels.
void writeCompletion(const patient::ReferenceCompletion& c, const patient::WholeModel& whole, const std::string& dir,
                     io::Report& report) {
  TriMesh skin = c.anatomy.skin;
  skin.vertexAttributes.real["fat_thickness"] = c.fatThickness;
  Eigen::VectorXi pulled(skin.V.rows());
  for (Eigen::Index v = 0; v < pulled.size(); ++v) pulled[v] = c.pulled[std::size_t(v)];
  skin.vertexAttributes.integer["pulled_by_scan"] = pulled;
  io::writeTriMesh(dir + "/completed_skin.vtp", skin);
  nlohmann::json groups = nlohmann::json::object(), bones = nlohmann::json::object();
  for (const transfer::BoneGroupMap& g : c.transfer.transferred.boneGroups)
    if (!std::isnan(g.targetRmsBeforeMm))
      groups[g.group] = {{"labels_rms_before_mm", g.targetRmsBeforeMm}, {"labels_rms_after_mm", g.targetRmsAfterMm}};
  for (const patient::RegisteredBone& b : whole.bones)
    bones[b.tissue] = {{"label", b.label},
                       {"vertices", b.registration.mesh.V.rows()},
                       {"label_boundary_to_bone_mean_mm", b.registration.boundaryToMeshMeanMm},
                       {"label_boundary_to_bone_max_mm", b.registration.boundaryToMeshMaxMm}};
  report.metric("completion", {{"tissues", c.anatomy.tissues.size()},
                               {"skin_vertices_pulled_by_scan", pulled.sum()},
                               {"scan_skin_to_completed_mean_mm", c.registration.skinMeanDistance},
                               {"scan_skin_to_completed_max_mm", c.registration.skinMaxDistance},
                               {"bone_groups_on_labels", groups},
                               {"bones_on_labels", bones}});
}

// Seed 000's rules on the whole model, in brief: whether each holds and its worst value and tissue.
nlohmann::json rulesReport(const transfer::AnatomyRules& r, const ReferenceAnatomy& model) {
  const auto name = [&](int t) { return t >= 0 ? model.tissues[std::size_t(t)].name : std::string(); };
  nlohmann::json pairs = nlohmann::json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(r.interpenetration.pairs.size(), 10); ++i) {
    const transfer::Interpenetration& p = r.interpenetration.pairs[i];
    pairs.push_back({{"tissues", {name(p.a), name(p.b)}},
                     {"depth_mm", p.depthMm},
                     {"reference_depth_mm", std::isnan(p.referenceDepthMm) ? nlohmann::json() : nlohmann::json(p.referenceDepthMm)}});
  }
  return {{"hold", r.holds()},
          {"outside", {{"holds", r.outside.holds}, {"vertices", r.outside.vertices}, {"outside", r.outside.outside},
                       {"at_cut", r.outside.outsideAtCut}, {"worst_mm", r.outside.worstMm},
                       {"worst_tissue", name(r.outside.worstTissue)}}},
          {"folds", {{"holds", r.folds.holds}, {"jacobian_min", r.folds.jacobian.minimum},
                     {"nonpositive_cells", r.folds.jacobian.nonPositiveCells}}},
          {"symmetry", {{"holds", r.symmetry.holds}, {"worst_excess_mm", r.symmetry.worstExcessMm},
                        {"worst_group", r.symmetry.worstGroup}}},
          {"straightness", {{"holds", r.straightness.holds}, {"worst_excess", r.straightness.worstExcess},
                            {"worst_bone", name(r.straightness.worstTissue)}}},
          {"interpenetration", {{"holds", r.interpenetration.holds}, {"worst_mm", r.interpenetration.worstMm},
                                {"worst_excess_mm", r.interpenetration.worstExcessMm}, {"deepest_pairs", pairs}}}};
}

// The pose asked for (posed world transforms of the rig's joints), or none.
struct Pose {
  std::vector<Eigen::Isometry3d> world;
  patient::PosedPatient posed;
};

// Everything into `dir` (a fresh private folder): the anatomy, the skin with its fat, the tissue classes,
// the rig, each fitted organ's markers and carried template, the posed patient, the report.
void writeOutputs(const PatientOptions& o, const Image& scan, const patient::VirtualPatient& p,
                  const std::optional<Pose>& pose, const std::string& dir, io::Report& report) {
  const ReferenceAnatomy& model = p.model();
  io::writeReferenceAnatomy(dir + "/anatomy", model, {});
  io::writeAnatomyGlb(dir + "/patient.glb", model, {});
  if (p.whole) io::writeReferenceAnatomy(dir + "/scan_anatomy", p.anatomy, {});
  TriMesh skin = p.anatomy.skin;
  skin.vertexAttributes.real["fat_thickness"] = p.fatThickness;
  io::writeTriMesh(dir + "/skin_fat.vtp", skin);
  io::writeLabelMap(dir + "/tissue_classes.nii.gz", p.tissueClasses);
  viz::writeSliceOverlayPng(scan, p.tissueClasses, dir + "/tissue_classes.png");
  nlohmann::json labelTissues = nlohmann::json::object(), fits = nlohmann::json::object();
  for (const auto& [label, tissues] : p.whole ? p.whole->labelTissues : p.labelTissues)
    for (const std::string& t : tissues) labelTissues[label].push_back("anatomy/" + io::tissueFile(t));
  if (p.completion) writeCompletion(*p.completion, *p.whole, dir, report);
  if (p.rules) report.metric("anatomy_rules", rulesReport(*p.rules, model));
  if (p.rig) {
    io::writeAnatomyRig(dir + "/rig", p.rig->rig, p.rig->meshes, {});
    report.metric("hip_joints", {{"left", p.rig->hipLeft}, {"right", p.rig->hipRight}});
    report.metric("rig", {{"tets", p.rig->rig.tets.T.rows()},
                          {"tet_vertices", p.rig->rig.tets.V.rows()},
                          {"joints", p.rig->rig.skeleton.joints.size()}});
  } else {
    report.metric("rig", {{"none", p.noRigBecause}});
  }
  if (!p.fits.empty()) fs::create_directories(dir + "/organs");
  for (const patient::FittedOrgan& f : p.fits) {
    const std::string stem = dir + "/organs/" + fs::path(io::tissueFile(f.organ)).stem().string();
    io::writeMarkers(stem + "_markers.mrk.json", icpMarkers(f));
    io::writeTriMesh(stem + "_template_fitted.obj", f.fit.carriedTemplate);
    fits[f.organ] = fitReport(f);
  }
  report.metric("label_tissues", labelTissues);
  report.metric("organ_fits", fits);
  nlohmann::json separation = nlohmann::json::array();
  for (const patient::OrganPairSeparation& s : p.organSeparation)
    if (s.penetratingBefore > 0)
      separation.push_back({{"organs", {p.fits[s.first].organ, p.fits[s.second].organ}},
                            {"penetrating_vertices_before", s.penetratingBefore},
                            {"penetrating_vertices_after", s.penetratingAfter},
                            {"max_depth_before_mm", s.maxDepthBefore},
                            {"max_depth_after_mm", s.maxDepthAfter},
                            {"max_displacement_mm", s.maxDisplacement}});
  report.metric("organ_separation", separation);
  report.metric("tissues", model.tissues.size());
  report.metric("skin_vertices", model.skin.V.rows());
  report.metric("scan_skin_cut_vertices", p.anatomy.skinCutVertices.size());
  report.metric("fat_thickness_mm", {{"mean", p.fatThickness.mean()}, {"max", p.fatThickness.maxCoeff()}});
  for (const auto& [stage, seconds] : p.stageSeconds) report.stage(stage, seconds);
  if (o.png) renderPng(model, dir + "/patient.png");
  if (o.png && p.whole) renderCompletionPng(p.whole->anatomy, p.anatomy, dir + "/completed.png");
  if (pose) writePosed(o, p, pose->posed, pose->world, dir + "/posed", report);
  report.write(dir + "/report.json", {});
}

void runPatient(const PatientOptions& o) {
  if (o.organTable.size() && o.organs.empty()) throw UsageError("patient: --organ-table needs --organs");
  if (fs::exists(o.out) && !o.common.force)
    throw UsageError(o.out + " exists; pass --force to replace it");
  if (fs::exists(o.out) && !fs::is_directory(o.out)) throw UsageError(o.out + " exists and is not a folder");
  if (o.png && !viz::canRenderSurfaces()) throw UsageError("patient: --png needs a display (run under xvfb-run)");
  if (!o.pose.empty() && !o.motion.empty()) throw UsageError("patient: give --pose or --motion, not both");
  if (!posing::isSkinningMethod(o.posing.method)) throw UsageError("patient: --method must be lbs, dqs, cor or fem");
  if (!o.pose.empty()) checkPoseJoints(o);
  for (const std::string& input : {o.scan, o.organs})
    if (!input.empty() && fs::exists(input) && fs::exists(o.out) &&
        fs::weakly_canonical(input).string().rfind(fs::weakly_canonical(o.out).string() + "/", 0) == 0)
      throw UsageError("patient: " + input + " lies inside --out, which would be replaced");
  io::Report report("patient");
  report.input("scan", o.scan);
  if (!o.organs.empty()) report.input("organs", o.organs);
  report.input("templates", o.templates);
  report.parameter("markers_per_organ", o.pipeline.organFit.markers);
  report.parameter("organ_tets", o.pipeline.organFit.targetTets);
  report.parameter("refits", o.pipeline.organFit.refits);
  Progress progress(o.common.progressStyle());

  const Image scan = io::readScan(o.scan);
  std::optional<LabelMap> organs;
  if (!o.organs.empty()) organs = io::readLabelMap(o.organs, o.organTable);
  const std::vector<patient::OrganTemplate> templates = readTemplates(o.templates);
  std::optional<Motion> motion;
  if (!o.motion.empty()) {
    motion = readMotion(o.motion);
    if (o.frame >= motion->frameCount())
      throw UsageError("patient: --frame " + std::to_string(o.frame) + " outside 0.." +
                       std::to_string(motion->frameCount() - 1) + " of " + o.motion);
  }
  std::optional<ReferenceAnatomy> reference;
  patient::VirtualPatientOptions pipeline = o.pipeline;
  for (rigging::RigOptions* rig : {&pipeline.rigging.modelRig, &pipeline.rigging.rig}) {
    if (o.rigTets > 0) rig->targetTets = o.rigTets;
    if (o.rigVoxelSize > 0) rig->voxelSize = o.rigVoxelSize;
  }
  if (o.complete) {
    progress.begin("reference", "the full-body reference");
    reference = fullBodyReference(o);
    progress.end();
    pipeline.fullBodyReference = &*reference;
  }
  const patient::VirtualPatient p = patient::buildVirtualPatient(scan, organs ? &*organs : nullptr, templates,
                                                                 pipeline, o.scan, o.organs, &progress);
  std::optional<Pose> pose;
  if (!o.pose.empty() || motion) {
    if (!p.rig) throw BadInput(o.organs.empty() ? o.scan : o.organs, "cannot pose the patient: " + p.noRigBecause);
    const Skeleton& skeleton = p.rig->rig.skeleton;
    pose.emplace();
    pose->world = motion ? RetargetedMotion(*motion, "", false, skeleton).pose(o.frame)
                         : posing::poseFromJointAngles(skeleton, posing::parseJointAngles(o.pose));
    progress.begin("pose", o.posing.method + " skinning, the scan re-posed");
    pose->posed = patient::posePatient(*p.rig, pose->world, scan, organs ? &*organs : nullptr, o.posing);
    progress.end();
  }

  writeFolderAtomically(o.out, o.common.writeOptions(),
                        [&](const std::string& staged) { writeOutputs(o, scan, p, pose, staged, report); });
  if (!o.common.report.empty()) o.common.finish(report);

  const ReferenceAnatomy& model = p.model();
  std::cout << std::fixed << std::setprecision(2) << "\nSummary\n  " << o.out << "/anatomy: "
            << model.tissues.size() << " tissues in the skin (" << model.skin.V.rows() << " vertices); patient.glb\n"
            << "  the scan's skin: subcutaneous fat " << p.fatThickness.mean() << " mm on average (skin_fat.vtp)\n";
  for (const patient::FittedOrgan& f : p.fits)
    std::cout << "  " << f.organ << ": " << f.templateSource << " fitted to " << f.fit.markers.rows()
              << " markers on its label, error " << f.fit.errorBefore.mean() << " -> " << f.fit.errorAfter.mean()
              << " mm (mean)\n";
  if (p.whole) {
    std::cout << "  beyond the scan the full-body reference, completed into the patient (the scan's skin "
              << p.completion->registration.skinMeanDistance << " mm from the completed skin on average)\n";
    for (const patient::RegisteredBone& b : p.whole->bones)
      std::cout << "  " << b.tissue << ": the reference's bone on label " << b.label << ", its boundary "
                << b.registration.boundaryToMeshMeanMm << " mm from the bone on average\n";
    const transfer::AnatomyRules& r = *p.rules;
    std::cout << "  seed 000's rules " << (r.holds() ? "hold" : "do not all hold") << ": " << r.outside.outside
              << " tissue vertices outside the skin (" << r.outside.outsideAtCut << " through the scan's cut), "
              << r.folds.jacobian.nonPositiveCells << " folded cells, deepest interpenetration beyond the reference's "
              << r.interpenetration.worstExcessMm << " mm (report.json anatomy_rules)\n";
  }
  if (p.rig)
    std::cout << "  rig/: " << p.rig->rig.tets.T.rows() << " tets, joints " << p.rig->hipLeft << " and "
              << p.rig->hipRight << " turn the hips (vesalius pose --anatomy " << o.out << "/rig)\n";
  else
    std::cout << "  no rig: " << p.noRigBecause << '\n';
  if (pose)
    std::cout << "  posed/: the model, scan and organ map posed by " << o.posing.method << "; "
              << pose->posed.quality.inverted << " inverted tets, skin volume change "
              << pose->posed.quality.skinVolumeChangePct << " %\n";
  std::cout << "  tissue classes in tissue_classes.nii.gz (tissue_classes.png); stage times and label_tissues in "
            << o.out << "/report.json\n";
}

void addPatientOptions(CLI::App& cmd, PatientOptions& o) {
  cmd.add_option("--templates", o.templates,
                 "Organ template library: a folder of closed surfaces named after their organ's label (liver.obj)")
      ->capture_default_str();
  cmd.add_option("--markers", o.pipeline.organFit.markers, "Markers spread over each fitted organ's label")
      ->check(CLI::Range(10, 10000))
      ->capture_default_str();
  cmd.add_option("--organ-tets", o.pipeline.organFit.targetTets, "About this many tets per organ template and refit")
      ->check(CLI::Range(500L, 1000000L))
      ->capture_default_str();
  cmd.add_option("--refits", o.pipeline.organFit.refits, "Refits of each organ fit from the shape it reached")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  cmd.add_option("--reference", o.reference,
                 "Full-body reference folder to complete into the patient beyond the scan (`vesalius reference "
                 "full-body`); default: built from the shipped MakeHuman body and OpenSim model");
  cmd.add_flag("!--no-reference", o.complete, "Do not complete the full-body reference into the patient");
  cmd.add_option("--pose", o.pose,
                 "Also pose the patient by joint angles in degrees, e.g. 'femur_l=-30,0,0; femur_r=-30,0,0' (both hips "
                 "flexed 30 degrees); the joints are OpenSim's: pelvis, femur_l, tibia_l, talus_l, torso, humerus_l, "
                 "ulna_l, hand_l and the same with _r (with --no-reference: pelvis, femur_left, femur_right, "
                 "vertebrae_L5 upward)");
  cmd.add_option("--motion", o.motion, "Or pose it by a frame of a BVH motion (CMU names or the rig's own)");
  cmd.add_option("--frame", o.frame, "The frame of --motion")->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd.add_option("--method", o.posing.method, "Skinning of the pose: cor (centres of rotation), dqs, lbs or fem")
      ->capture_default_str();
  cmd.add_option("--rig-tets", o.rigTets, "About this many tets in the rig (default 20000)")
      ->check(CLI::Range(2000L, 2000000L));
  cmd.add_option("--rig-voxel-size", o.rigVoxelSize,
                 "Voxels of the body and bones the rig is meshed from, mm (default 8 for the whole model, 6 with "
                 "--no-reference, where the scan's own are used if coarser)")
      ->check(CLI::PositiveNumber);
  cmd.add_flag("--png", o.png,
               "Also write patient.png (the model inside the translucent skin) and completed.png (the same with "
               "the scan's skin in blue); needs a display");
  addCommonOptions(cmd, o.common);
}

const char* kOutputs =
    "Writes DIR/anatomy/ (the whole model: the patient's skin, bones and organs inside the scan, the full-body "
    "reference completed into the patient beyond it; the format `vesalius transfer` reads), patient.glb (the same "
    "for any glTF viewer), scan_anatomy/ (the model inside the scan alone), skin_fat.vtp (fat thickness per skin "
    "vertex), completed_skin.vtp, tissue_classes.nii.gz and .png, rig/ (what `vesalius pose` and vesalius-poser "
    "pose), organs/ (markers and fitted templates), with --pose or --motion posed/ (the posed model, scan and organ "
    "map) and report.json (label_tissues, hip_joints, organ fits, pose quality, stage times). "
    "docs/virtual-patient.md says what the model holds.";

}  // namespace

void addPatientCommand(CLI::App& app) {
  auto o = std::make_shared<PatientOptions>();
  CLI::App* cmd = app.add_subcommand("patient", "One patient's CT in, that patient's anatomy out (the virtual patient)");
  cmd->add_option("--scan", o->scan, "The patient's CT (NIfTI, NRRD, MetaImage, DICOM folder)")->required();
  cmd->add_option("--organs", o->organs,
                  "Organ and bone label map of the same scan, as TotalSegmentator writes it (v1 or v2 names)");
  cmd->add_option("--organ-table", o->organTable, "Its label table (default: the one beside it)");
  cmd->add_option("--out", o->out, "Output folder DIR (written whole at the end, or not at all)")->required();
  addPatientOptions(*cmd, *o);
  cmd->footer(std::string("Example:\n"
                          "  vesalius patient --scan ct.nii.gz --organs seg.nii.gz --organ-table labels_total_v1.tsv "
                          "--out patient --pose 'femur_l=-30,0,0; femur_r=-30,0,0'\n") +
              kOutputs);
  cmd->callback([o] { runPatient(*o); });
}

void addDemoCommand(CLI::App& app) {
  auto o = std::make_shared<PatientOptions>();
  o->scan = VESALIUS_DATA_DIR "/ct-abdomen-pelvis/example_ct.nii.gz";
  o->organs = VESALIUS_DATA_DIR "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz";
  o->organTable = VESALIUS_DATA_DIR "/ct-abdomen-pelvis/labels_total_v1.tsv";
  o->out = "demo-output";
  CLI::App* cmd = app.add_subcommand(
      "demo", "The main job on the shipped example CT: `vesalius patient` on it and its TotalSegmentator labels");
  cmd->add_option("--scan", o->scan, "CT scan to use instead of the shipped one")->capture_default_str();
  cmd->add_option("--organs", o->organs, "Organ and bone label map of that scan")->capture_default_str();
  cmd->add_option("--organ-table", o->organTable, "Its label table")->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder DIR")->capture_default_str();
  addPatientOptions(*cmd, *o);
  cmd->footer(std::string("Example:\n  vesalius demo --out demo-output --force\n"
                          "Most of its time goes to the organ fits and the full-body reference's completion. ") +
              kOutputs);
  cmd->callback([o] { runPatient(*o); });
}

}  // namespace vesalius::cli
