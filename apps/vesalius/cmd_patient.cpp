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

// The completed body inside its translucent skin, the scan's own skin over it: where the patient ends and
// the reference goes on.
void renderCompletionPng(const patient::ReferenceCompletion& c, const ReferenceAnatomy& scan, const std::string& path) {
  std::vector<viz::SurfaceLayer> layers;
  for (const ReferenceTissue& t : c.anatomy.tissues) layers.push_back({&t.mesh, tissueKindColour(t.kind), 1.0});
  layers.push_back({&c.anatomy.skin, kSkinColour, 0.15});
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
  const ReferenceAnatomy anatomy = posedAnatomy(p.anatomy, posed);
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

// --pose's syntax and joint names, before the work: the rig's joints are the pelvis, the femurs and the
// lumbar vertebrae of the organ map (posing/skeleton_from_bones.h).
void checkPoseJoints(const PatientOptions& o) {
  const posing::SkeletonFromBonesOptions& bones = o.pipeline.rigging.bones;
  std::vector<std::string> joints{"pelvis", bones.femurLeft, bones.femurRight};
  joints.insert(joints.end(), bones.spine.begin(), bones.spine.end());
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

// DIR/completed/: the full-body reference completed into the patient (a reference folder), its skin with
// the fat and the vertices the scan's skin pulled.
void writeCompletion(const patient::ReferenceCompletion& c, const std::string& dir, io::Report& report) {
  io::writeReferenceAnatomy(dir + "/completed", c.anatomy, {});
  TriMesh skin = c.anatomy.skin;
  skin.vertexAttributes.real["fat_thickness"] = c.fatThickness;
  Eigen::VectorXi pulled(skin.V.rows());
  for (Eigen::Index v = 0; v < pulled.size(); ++v) pulled[v] = c.pulled[std::size_t(v)];
  skin.vertexAttributes.integer["pulled_by_scan"] = pulled;
  io::writeTriMesh(dir + "/completed_skin.vtp", skin);
  report.metric("completion", {{"tissues", c.anatomy.tissues.size()},
                               {"skin_vertices_pulled_by_scan", pulled.sum()},
                               {"scan_skin_to_completed_mean_mm", c.registration.skinMeanDistance},
                               {"scan_skin_to_completed_max_mm", c.registration.skinMaxDistance}});
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
  io::writeReferenceAnatomy(dir + "/anatomy", p.anatomy, {});
  io::writeAnatomyGlb(dir + "/patient.glb", p.anatomy, {});
  TriMesh skin = p.anatomy.skin;
  skin.vertexAttributes.real["fat_thickness"] = p.fatThickness;
  io::writeTriMesh(dir + "/skin_fat.vtp", skin);
  io::writeLabelMap(dir + "/tissue_classes.nii.gz", p.tissueClasses);
  viz::writeSliceOverlayPng(scan, p.tissueClasses, dir + "/tissue_classes.png");
  nlohmann::json labelTissues = nlohmann::json::object(), fits = nlohmann::json::object();
  for (const auto& [label, tissues] : p.labelTissues)
    for (const std::string& t : tissues) labelTissues[label].push_back("anatomy/" + io::tissueFile(t));
  if (p.completion) writeCompletion(*p.completion, dir, report);
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
  report.metric("tissues", p.anatomy.tissues.size());
  report.metric("skin_vertices", p.anatomy.skin.V.rows());
  report.metric("skin_cut_vertices", p.anatomy.skinCutVertices.size());
  report.metric("fat_thickness_mm", {{"mean", p.fatThickness.mean()}, {"max", p.fatThickness.maxCoeff()}});
  for (const auto& [stage, seconds] : p.stageSeconds) report.stage(stage, seconds);
  if (o.png) renderPng(p.anatomy, dir + "/patient.png");
  if (o.png && p.completion) renderCompletionPng(*p.completion, p.anatomy, dir + "/completed.png");
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

  const TemporaryFolder temporary(o.out);
  const std::string staged = temporary.path() + "/" + fs::path(o.out).filename().string();
  fs::create_directories(staged);
  writeOutputs(o, scan, p, pose, staged, report);
  if (fs::exists(o.out)) fs::remove_all(o.out);
  fs::rename(staged, o.out);
  if (!o.common.report.empty()) o.common.finish(report);

  std::cout << std::fixed << std::setprecision(2) << "\nSummary\n  " << o.out << "/anatomy: "
            << p.anatomy.tissues.size() << " tissues in the skin (" << p.anatomy.skin.V.rows()
            << " vertices, subcutaneous fat " << p.fatThickness.mean() << " mm on average, skin_fat.vtp); patient.glb\n";
  for (const patient::FittedOrgan& f : p.fits)
    std::cout << "  " << f.organ << ": " << f.templateSource << " fitted to " << f.fit.markers.rows()
              << " markers on its label, error " << f.fit.errorBefore.mean() << " -> " << f.fit.errorAfter.mean()
              << " mm (mean)\n";
  if (p.completion)
    std::cout << "  completed/: the full-body reference completed into the patient (" << p.completion->anatomy.tissues.size()
              << " tissues; the scan's skin " << p.completion->registration.skinMeanDistance
              << " mm from the completed skin on average)\n";
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
                 "Also pose the patient by joint angles in degrees, e.g. 'femur_left=-30,0,0; femur_right=-30,0,0' "
                 "(both hips flexed 30 degrees); the joints are pelvis, femur_left, femur_right, vertebrae_L5 upward");
  cmd.add_option("--motion", o.motion, "Or pose it by a frame of a BVH motion (CMU names or the rig's own)");
  cmd.add_option("--frame", o.frame, "The frame of --motion")->check(CLI::NonNegativeNumber)->capture_default_str();
  cmd.add_option("--method", o.posing.method, "Skinning of the pose: cor (centres of rotation), dqs, lbs or fem")
      ->capture_default_str();
  cmd.add_option("--rig-tets", o.pipeline.rigging.rig.targetTets, "About this many tets in the rig")
      ->check(CLI::Range(2000L, 2000000L))
      ->capture_default_str();
  cmd.add_option("--rig-voxel-size", o.pipeline.rigging.rig.voxelSize,
                 "Voxels of the body and bones the rig is meshed from, mm (the scan's own if coarser)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd.add_flag("--png", o.png,
               "Also write patient.png (the anatomy inside the translucent skin) and completed.png (the completed body, "
               "the scan's skin in blue); needs a display");
  addCommonOptions(cmd, o.common);
}

const char* kOutputs =
    "Writes DIR/anatomy/ (skin and every tissue, the format `vesalius transfer` reads), patient.glb (the same for "
    "any glTF viewer), skin_fat.vtp (fat thickness per skin vertex), tissue_classes.nii.gz and .png, rig/ (what "
    "`vesalius pose` and vesalius-poser pose), organs/ (markers and fitted templates), completed/ and "
    "completed_skin.vtp (the full-body reference completed into the patient beyond the scan), with --pose or --motion "
    "posed/ (the posed model, scan and organ map) and report.json (label_tissues, hip_joints, organ fits, pose "
    "quality, stage times). "
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
                          "--out patient --pose 'femur_left=-30,0,0; femur_right=-30,0,0'\n") +
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
                          "Takes about a minute and a half on 2 cores, most of it the liver fit. ") +
              kOutputs);
  cmd->callback([o] { runPatient(*o); });
}

}  // namespace vesalius::cli
