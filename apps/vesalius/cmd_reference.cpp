// vesalius reference torso: a reference anatomy for anatomy transfer (seed 000 §3, Fig. 2.c) built from a
// labelled CT: the body's surface as the skin, every label of the segmentation as a bone, muscle or organ.
// vesalius reference full-body: MakeHuman's skin with an OpenSim model's bones placed inside it
// (patient/full_body_reference.h).
#include "common.h"
#include "full_body_sources.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/patient/full_body_reference.h"
#include "vesalius/patient/scan_anatomy.h"

#include <iostream>

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
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
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

// The full-body reference (seed 000 §3; patient/full_body_reference.h): the files read, the reference
// built, its bones' moves inside the skin reported.
void runFullBody(const FullBodyOptions& o) {
  checkOutputFolder(o.out, o.common.writeOptions());  // before the work; written whole at the end
  io::Report report("reference full-body");
  report.input("skin", o.skin);
  report.input("skeleton", o.skeleton);
  report.input("model", o.model);
  patient::FullBodyReference built;
  {
    const patient::FullBodySources sources = readFullBodySources(o.skin, o.skeleton, o.baseMesh, o.model);
    auto timer = report.time("placement");
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
  report.metric("bones_into_skin", changes);
  report.metric("bone_vertices_outside_skin_before", built.outsideBefore);
  report.metric("bone_vertices_outside_skin", built.outsideAfter);
  io::writeReferenceAnatomy(o.out, anatomy, o.common.writeOptions());
  report.output("reference", o.out);
  report.metric("bones", anatomy.tissues.size());
  report.metric("points", anatomy.points.size());
  report.metric("head_slices", built.headSlices);
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
