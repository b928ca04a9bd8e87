// vesalius reference torso: a reference anatomy for anatomy transfer (Dicko et al. 2013, §3, Fig. 2.c) built from a
// labelled CT: the body's surface as the skin, every label of the segmentation as a bone, muscle or organ.
// vesalius reference full-body: MakeHuman's skin with an OpenSim model's bones placed inside it
// (patient/full_body_reference.h). vesalius reference organs: a labelled CT's organs and muscles carried
// into that reference's skin (patient/reference_organs.h), the folder shipped as templates/reference-organs/.
#include "command_runner.h"
#include "common.h"
#include "full_body_sources.h"
#include "label_map_input.h"
#include "shipped_data.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/patient/full_body_reference.h"
#include "vesalius/patient/reference_organs.h"
#include "vesalius/patient/scan_anatomy.h"

#include <iostream>

namespace vesalius::cli {

namespace {

// The organs and muscles of a reference (the rest are bones).
long softTissueCount(const ReferenceAnatomy& anatomy) {
  long n = 0;
  for (const ReferenceTissue& t : anatomy.tissues) n += t.kind == TissueKind::Organ || t.kind == TissueKind::Muscle;
  return n;
}

struct ReferenceOptions {
  std::string scan, labels, table, grid, out, name;
  int skinFaces = 20000, tissueFaces = 3000;
  CommonOptions common;
};

struct FullBodyOptions {
  std::string skin, skeleton, baseMesh, model, organMeshes, out;
  CommonOptions common;
};

struct OrgansOptions {
  std::string scan, organs, organTable, grid, reference, out, templates = shippedTemplates("organs");
  patient::ReferenceOrgansOptions method;
  CommonOptions common;
};

void runReference(const ReferenceOptions& o, CommandRun& run) {
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
  run.report.input("scan", o.scan);
  run.report.input("labels", o.labels);
  run.report.parameter("skin_faces", o.skinFaces);
  run.report.parameter("tissue_faces", o.tissueFaces);
  const Image ct = io::readScan(o.scan);
  const LabelMap labels = readLabelsOption(o.labels, o.table, o.grid, run.report);
  patient::ScanAnatomyOptions surfaces;
  surfaces.skinFaces = o.skinFaces;
  surfaces.tissueFaces = o.tissueFaces;
  ReferenceAnatomy anatomy;
  {
    auto timer = run.report.time("skin and tissues");
    anatomy = patient::scanAnatomy(ct, labels, surfaces, o.scan, o.labels, &run.progress);
  }
  anatomy.name = o.name.empty() ? "torso (" + o.scan + ")" : o.name;
  io::writeReferenceAnatomy(o.out, anatomy, o.common.writeOptions());
  run.report.output("reference", o.out);
  int bones = 0;
  for (const ReferenceTissue& t : anatomy.tissues) bones += t.kind == TissueKind::Bone;
  run.report.metric("tissues", anatomy.tissues.size());
  run.report.metric("bones", bones);
  run.report.metric("skin_vertices", anatomy.skin.V.rows());
  run.report.metric("skin_cut_vertices", anatomy.skinCutVertices.size());
  std::cout << o.out << ": skin of " << anatomy.skin.V.rows() << " vertices (" << anatomy.skinCutVertices.size()
            << " on the field of view's cut), " << anatomy.tissues.size()
            << " tissues (" << bones << " bones), sagittal normal " << anatomy.sagittal.normal.transpose() << "\n";
}

// The full-body reference (Dicko et al. 2013, §3; patient/full_body_reference.h): the files read, the reference
// built, its bones' moves inside the skin reported.
void runFullBody(const FullBodyOptions& o, CommandRun& run) {
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
  run.report.input("skin", o.skin);
  run.report.input("skeleton", o.skeleton);
  run.report.input("model", o.model);
  patient::FullBodyReference built;
  {
    const patient::FullBodySources sources = readFullBodySources(o.skin, o.skeleton, o.baseMesh, o.model, o.organMeshes);
    auto timer = run.report.time("placement");
    built = patient::buildFullBodyReference(sources, o.skeleton);
  }
  const ReferenceAnatomy& anatomy = built.anatomy;
  nlohmann::json changes;
  for (const patient::BoneUnitIntoSkin& u : built.intoSkin)
    changes[u.unit] = {{"outside_before", u.outsideBefore}, {"outside_after_change", u.outsideAfterChange},
                       {"outside_after", u.outsideAfter}, {"bend_largest_mm", u.bendLargestMm},
                       {"scale", u.scale}, {"turn_degrees", u.turnDegrees},
                       {"centroid_shift_mm", u.centroidShiftMm}, {"joints", u.joints},
                       {"joint_shift_mm", u.jointShiftMm}};
  run.report.metric("bones_into_skin", changes);
  run.report.metric("bone_vertices_outside_skin_before", built.outsideBefore);
  run.report.metric("bone_vertices_outside_skin", built.outsideAfter);
  io::writeReferenceAnatomy(o.out, anatomy, o.common.writeOptions());
  run.report.output("reference", o.out);
  run.report.metric("bones", anatomy.tissues.size() - softTissueCount(anatomy));
  run.report.metric("organs_and_muscles", softTissueCount(anatomy));
  run.report.metric("points", anatomy.points.size());
  run.report.metric("head_slices", built.headSlices);
  const long soft = softTissueCount(anatomy);
  std::cout << o.out << ": skin of " << anatomy.skin.V.rows() << " vertices, " << anatomy.tissues.size() - soft
            << " bone meshes, " << soft << " organs and muscles, " << anatomy.points.size()
            << " points (muscle paths and joint centres)\n";
}

// The organs and muscles of a labelled CT carried into the full-body reference (patient/reference_organs.h).
void runOrgans(const OrgansOptions& o, CommandRun& run) {
  for (const std::string& input : {o.scan, o.organs, o.organTable, o.reference, o.templates})
    if (!input.empty()) protectInput(input);
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
  run.report.input("scan", o.scan);
  run.report.input("organs", o.organs);
  run.report.input("templates", o.templates);
  const Image ct = io::readScan(o.scan);
  const LabelMap organs = readLabelsOption(o.organs, o.organTable, o.grid, run.report);
  const std::vector<patient::OrganTemplate> templates = readOrganTemplates(o.templates);
  ReferenceAnatomy reference;
  if (!o.reference.empty()) {
    run.report.input("reference", o.reference);
    reference = io::readReferenceAnatomy(o.reference);
  } else {
    run.progress.begin("reference", "the full-body reference");
    reference = shippedFullBodyReference(false);
    run.progress.end();
  }
  const patient::ReferenceOrgans made =
      patient::referenceOrgans(ct, organs, templates, reference, o.method, o.scan, o.organs, &run.progress);
  io::writeReferenceAnatomy(o.out, made.anatomy, o.common.writeOptions());
  run.report.output("reference", o.out);
  nlohmann::json tissues;
  long outside = 0;
  for (const patient::CarriedTissue& t : made.carried) {
    tissues[t.name] = {{"kind", tissueKindName(t.kind)}, {"vertices", t.vertices},
                       {"outside_skin_carried", t.outsideCarried}, {"outside_skin", t.outsideSkin}};
    outside += t.outsideSkin;
  }
  run.report.metric("tissues", tissues);
  run.report.metric("scan_skin_to_completed_mean_mm", made.scanSkinToCompletedMeanMm);
  run.report.metric("bend_largest_mm", made.bendLargestMm);
  nlohmann::json stages;
  for (const auto& [stage, seconds] : made.stageSeconds) stages[stage] = seconds;
  run.report.metric("stage_seconds", stages);
  std::cout << o.out << ": " << made.anatomy.tissues.size() << " organs and muscles in the reference's skin ("
            << outside << " vertices outside it)\n";
}

}  // namespace

void addReferenceCommand(CLI::App& app) {
  auto o = std::make_shared<ReferenceOptions>();
  CLI::App* cmd = app.add_subcommand("reference", "Build a reference anatomy for `vesalius transfer`");
  cmd->require_subcommand(1);
  CLI::App* torso = cmd->add_subcommand("torso", "Reference anatomy from a labelled CT: body surface as skin, every label as a tissue");
  torso->add_option("--scan", o->scan, "The CT (NIfTI, NRRD, MetaImage, DICOM folder)")->required();
  addLabelsOption(*torso, o->labels, o->grid,
                  "Its label map (TotalSegmentator names: bones, muscles, organs); an RT Structure Set with --grid")
      ->required();
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
  torso->callback([o] { runCommand("reference torso", o->common, [&](CommandRun& run) { runReference(*o, run); }); });

  auto f = std::make_shared<FullBodyOptions>();
  CLI::App* full = cmd->add_subcommand("full-body", "Reference anatomy from a MakeHuman skin with an OpenSim skeleton placed inside it");
  const FullBodyFiles shipped = shippedFullBodyFiles();
  f->skin = shipped.skin;
  f->skeleton = shipped.skeleton;
  f->model = shipped.model;
  full->add_option("--skin", f->skin, "MakeHuman body (.obj, decimetres, +Y up); default: the shipped neutral body")
      ->capture_default_str();
  full->add_option("--skeleton", f->skeleton, "MakeHuman default rig (.mhskel); default: the shipped one")->capture_default_str();
  full->add_option("--base-mesh", f->baseMesh, "MakeHuman base.obj for the rig, and the uv of a skin without them (default: beside the rig)");
  full->add_option("--model", f->model, "OpenSim model (.osim) with its Geometry folder beside it; default: the shipped "
                                        "Rajagopal et al. 2016 model")
      ->capture_default_str();
  full->add_option("--organ-meshes", f->organMeshes,
                    "Reference folder of organs and muscles made for this skin (`vesalius reference organs`; "
                    "templates/reference-organs for the shipped neutral body), added to the bones");
  full->add_option("--out", f->out, "Reference folder to write")->required();
  addCommonOptions(*full, f->common);
  full->footer(
      "Examples:\n  vesalius reference full-body --out body-reference       # the shipped body and model\n"
      "  vesalius reference full-body --skin my_makehuman_body.obj --out my-reference\n"
      "The skeleton is placed by the body frame of the GRAPP 2012 skeleton-alignment paper and per-bone similarity fits; see docs/methods/skeleton-alignment.md.");
  full->callback([f] { runCommand("reference full-body", f->common, [&](CommandRun& run) { runFullBody(*f, run); }); });

  auto g = std::make_shared<OrgansOptions>();
  CLI::App* organs = cmd->add_subcommand(
      "organs", "Organs and muscles of a labelled CT carried into the full-body reference's skin (its virtual patient, transferred back)");
  organs->add_option("--scan", g->scan, "The CT (NIfTI, NRRD, MetaImage, DICOM folder)")->required();
  addLabelsOption(*organs, g->organs, g->grid,
                  "Its organ label map (TotalSegmentator's names); an RT Structure Set with --grid", "--organs")
      ->required();
  organs->add_option("--organ-table", g->organTable, "Its label table (default: the one beside it)");
  organs->add_option("--templates", g->templates, "Organ template library fitted to the labels")->capture_default_str();
  organs->add_option("--reference", g->reference,
                     "Full-body reference folder without organs (default: built from the shipped MakeHuman body and OpenSim model)");
  organs->add_option("--markers", g->method.patient.organFit.markers, "Markers spread over each fitted organ's label")
      ->check(CLI::Range(10, 10000))
      ->capture_default_str();
  organs->add_option("--organ-tets", g->method.patient.organFit.targetTets, "About this many tets per organ fit")
      ->check(CLI::Range(500L, 1000000L))
      ->capture_default_str();
  organs->add_option("--refits", g->method.patient.organFit.refits, "Refits of each organ fit")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  organs->add_option("--tissue-faces", g->method.patient.surfaces.tissueFaces, "Triangles of each label's surface")
      ->check(CLI::Range(200, 100000))
      ->capture_default_str();
  organs->add_option("--out", g->out, "Reference folder to write (the reference's skin, tissues/<organ>.obj)")->required();
  addCommonOptions(*organs, g->common);
  organs->footer(
      "Example:\n  vesalius reference organs --scan testdata/ct-abdomen-pelvis/example_ct.nii.gz \\\n"
      "    --organs testdata/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz \\\n"
      "    --organ-table testdata/ct-abdomen-pelvis/labels_total_v1.tsv --out templates/reference-organs\n"
      "Keeps the abdominal and pelvic organs, their vessels and the gluteal, iliopsoas and back muscles; "
      "see docs/virtual-patient.md.");
  organs->callback([g] { runCommand("reference organs", g->common, [&](CommandRun& run) { runOrgans(*g, run); }); });
}

}  // namespace vesalius::cli
