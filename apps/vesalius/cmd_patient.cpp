// vesalius patient: one patient's CT or MRI (and its organ/bone segmentation) in, that patient's anatomy out
// (patient/virtual_patient.h). Reads the inputs and the organ template library, runs the pipeline, writes
// the output folder whole or not at all. vesalius demo is the same command on the shipped CT and labels.
#include "command_runner.h"
#include "common.h"
#include "full_body_sources.h"
#include "label_map_input.h"
#include "modality_option.h"
#include "patient_outputs.h"
#include "shipped_data.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/patient/virtual_patient.h"
#include "vesalius/posing/joint_angles.h"
#include "vesalius/posing/rig_poser.h"
#include "vesalius/posing/skeleton_from_bone_meshes.h"
#include "vesalius/rigging/rig_session.h"
#include "vesalius/viz/surface_render.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct PatientOptions {
  std::string scan, organs, organTable, grid, out, templates = shippedTemplates("organs");
  std::string modality = "auto";
  std::string pose, motion;  // joint angles, or a BVH motion and its frame
  int frame = 0;
  std::string reference;     // a full-body reference folder; empty: built from the shipped sources
  bool complete = true;      // complete the full-body reference into the patient
  bool referenceOrgans = false;  // the built reference holds the shipped organs and muscles
  bool png = false;
  long rigTets = 0;        // 0: the rig's own default
  double rigVoxelSize = 0;  // 0: the rig's own default
  patient::VirtualPatientOptions pipeline;
  patient::PatientPoseOptions posing;
  CommonOptions common;
};

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
// MakeHuman body and OpenSim model as `vesalius reference full-body` builds it, with --reference-organs with
// the shipped organs and muscles made for that body (templates/reference-organs/, patient/reference_organs.h).
// With --organs the patient's own organs take the place of the reference's of the same names
// (patient/whole_model.h).
ReferenceAnatomy fullBodyReference(const PatientOptions& o) {
  if (!o.reference.empty()) return io::readReferenceAnatomy(o.reference);
  return shippedFullBodyReference(o.referenceOrgans);
}

void runPatient(const PatientOptions& o, CommandRun& run) {
  if (o.organTable.size() && o.organs.empty()) throw UsageError("patient: --organ-table needs --organs");
  for (const std::string& input : {o.scan, o.organs, o.organTable, o.reference, o.motion, o.templates})
    if (!input.empty()) protectInput(input);
  checkOutputFolder(o.out, o.common.writeOptions());
  if (o.png && !viz::canRenderSurfaces()) throw UsageError("patient: --png needs a display (run under xvfb-run)");
  if (!o.pose.empty() && !o.motion.empty()) throw UsageError("patient: give --pose or --motion, not both");
  if (!posing::isSkinningMethod(o.posing.method)) throw UsageError("patient: --method must be lbs, dqs, cor or fem");
  if (!o.pose.empty()) checkPoseJoints(o);
  run.report.input("scan", o.scan);
  if (!o.organs.empty()) run.report.input("organs", o.organs);
  run.report.input("templates", o.templates);
  run.report.parameter("markers_per_organ", o.pipeline.organFit.markers);
  run.report.parameter("organ_tets", o.pipeline.organFit.targetTets);
  run.report.parameter("refits", o.pipeline.organFit.refits);

  const Image scan = io::readScan(o.scan);
  patient::VirtualPatientOptions pipeline = o.pipeline;
  pipeline.surfaces.modality = resolveModality(o.modality, scan);
  run.report.parameter("modality", segmentation::modalityName(pipeline.surfaces.modality));
  std::optional<LabelMap> organs;
  if (!o.organs.empty()) organs = readLabelsOption(o.organs, o.organTable, o.grid, run.report);
  const std::vector<patient::OrganTemplate> templates = readOrganTemplates(o.templates);
  std::optional<Motion> motion;
  if (!o.motion.empty()) {
    motion = io::readBvh(o.motion, std::cerr);
    if (o.frame >= motion->frameCount())
      throw UsageError("patient: --frame " + std::to_string(o.frame) + " outside 0.." +
                       std::to_string(motion->frameCount() - 1) + " of " + o.motion);
  }
  for (rigging::RigOptions* rig : {&pipeline.rigging.modelRig, &pipeline.rigging.rig}) {
    if (o.rigTets > 0) rig->targetTets = o.rigTets;
    if (o.rigVoxelSize > 0) rig->voxelSize = o.rigVoxelSize;
  }
  // Bad inputs refused at once, before the reference and the pipeline take their minutes.
  patient::checkVirtualPatientInputs(scan, organs ? &*organs : nullptr, templates, pipeline, o.complete,
                                     !o.pose.empty() || motion.has_value(), o.scan, o.organs);
  std::optional<ReferenceAnatomy> reference;
  // One bar over the command: the reference built, the pipeline's stages, the pose and the writing, by
  // their seconds on the shipped CT.
  StagePlan plan;
  if (o.complete) plan.emplace_back("reference", 10);
  for (const auto& stage : patient::virtualPatientStages(organs ? &*organs : nullptr, templates, pipeline, o.complete))
    plan.push_back(stage);
  if (!o.pose.empty() || motion) plan.emplace_back("pose", 10);
  plan.emplace_back("writing", 10);
  run.progress.plan(plan);
  if (o.complete) {
    run.progress.begin("reference", "the full-body reference");
    reference = fullBodyReference(o);
    run.progress.end();
    pipeline.fullBodyReference = &*reference;
  }
  const patient::VirtualPatient p = patient::buildVirtualPatient(scan, organs ? &*organs : nullptr, templates,
                                                                 pipeline, o.scan, o.organs, &run.progress);
  std::optional<PatientPose> pose;
  if (!o.pose.empty() || motion) {
    if (!p.rig) throw BadInput(o.organs.empty() ? o.scan : o.organs, "cannot pose the patient: " + p.noRigBecause);
    const Skeleton& skeleton = p.rig->rig.skeleton;
    pose.emplace();
    pose->method = o.posing.method;
    pose->angles = o.pose;
    pose->motion = o.motion;
    pose->frame = o.frame;
    pose->world = motion ? rigging::RetargetedMotion(*motion, "", false, skeleton).pose(o.frame)
                         : posing::poseFromJointAngles(skeleton, posing::parseJointAngles(o.pose));
    run.progress.begin("pose", o.posing.method + " skinning, the scan re-posed");
    pose->posed = patient::posePatient(*p.rig, pose->world, scan, organs ? &*organs : nullptr, o.posing);
    run.progress.end();
  }

  run.progress.begin("writing", "the patient's folder");
  writeFolderAtomically(o.out, o.common.writeOptions(),
                        [&](const std::string& staged) { writePatientFolder(scan, p, pose ? &*pose : nullptr, o.png, staged, run.report); });
  run.progress.end();

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
    std::cout << "  Dicko et al.'s rules " << (r.holds() ? "hold" : "do not all hold") << ": " << r.outside.outside
              << " tissue vertices outside the skin (" << r.outside.outsideAtCut << " through the scan's cut), "
              << r.folds.jacobian.nonPositiveCells << " folded cells, deepest interpenetration beyond the reference's "
              << r.interpenetration.worstExcessMm << " mm (report.json anatomy_rules)\n";
  }
  if (p.rig) {
    std::cout << "  rig/: " << p.rig->rig.tets.T.rows() << " tets, joints " << p.rig->hipLeft << " and "
              << p.rig->hipRight << " turn the hips (vesalius pose --anatomy " << o.out << "/rig)\n";
    warnIfOverTetTarget(long(p.rig->rig.tets.T.rows()),
                        (o.complete ? pipeline.rigging.modelRig : pipeline.rigging.rig).targetTets, "--rig-tets");
  } else {
    std::cout << "  no rig: " << p.noRigBecause << '\n';
  }
  if (pose)
    std::cout << "  posed/: the model, scan and organ map posed by " << o.posing.method << "; "
              << pose->posed.quality.inverted << " inverted tets, skin volume change "
              << pose->posed.quality.skinVolumeChangePct << " %\n";
  std::cout << "  tissue classes in tissue_classes.nii.gz (tissue_classes.png); stage times and label_tissues in "
            << o.out << "/report.json\n";
}

void addPatientOptions(CLI::App& cmd, PatientOptions& o) {
  addModalityOption(cmd, o.modality);
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
  CLI::Option* reference =
      cmd.add_option("--reference", o.reference,
                     "Full-body reference folder to complete into the patient beyond the scan (`vesalius reference "
                     "full-body`); default: built from the shipped MakeHuman body and OpenSim model");
  cmd.add_flag("!--no-reference", o.complete, "Do not complete the full-body reference into the patient")->excludes(reference);
  cmd.add_flag("--reference-organs", o.referenceOrgans,
               "The built full-body reference with the shipped organs and muscles (templates/reference-organs/): "
               "those --organs lacks (all without --organs) come from it; they lie too far up the body "
               "(docs/virtual-patient.md). A --reference folder holds its own (`reference full-body --organ-meshes`)")
      ->excludes(reference);
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
  CLI::App* cmd =
      app.add_subcommand("patient", "One patient's CT or MRI in, that patient's anatomy out (the virtual patient)");
  cmd->add_option("--scan", o->scan, "The patient's CT or MRI (NIfTI, NRRD, MetaImage, DICOM folder)")->required();
  addLabelsOption(*cmd, o->organs, o->grid,
                  "Organ and bone label map of the same scan, as TotalSegmentator writes it (v1 or v2 names); an RT "
                  "Structure Set with --grid",
                  "--organs");
  cmd->add_option("--organ-table", o->organTable, "Its label table (default: the one beside it)");
  cmd->add_option("--out", o->out, "Output folder DIR (written whole at the end, or not at all)")->required();
  addPatientOptions(*cmd, *o);
  cmd->footer(std::string("Example:\n"
                          "  vesalius patient --scan ct.nii.gz --organs seg.nii.gz --organ-table labels_total_v1.tsv "
                          "--out patient --pose 'femur_l=-30,0,0; femur_r=-30,0,0'\n"
                          "  vesalius patient --scan mr.nii.gz --organs mr_seg.nii.gz --organ-table labels_total_mr.tsv "
                          "--out mr-patient\n") +
              kOutputs);
  cmd->callback([o] { runCommand("patient", o->common, [&](CommandRun& run) { runPatient(*o, run); }); });
}

void addDemoCommand(CLI::App& app) {
  auto o = std::make_shared<PatientOptions>();
  o->scan = shippedData("ct-abdomen-pelvis/example_ct.nii.gz");
  o->organs = shippedData("ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz");
  o->organTable = shippedData("ct-abdomen-pelvis/labels_total_v1.tsv");
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
  cmd->callback([o] { runCommand("patient", o->common, [&](CommandRun& run) { runPatient(*o, run); }); });
}

}  // namespace vesalius::cli
