// vesalius demo: the main job on the shipped data, from a scan to a fitted organ. Segments the example CT
// into tissue classes (label map, skin surface, one closed surface per inner class, a picture), spreads
// ICP markers over the liver label of the scan's organ segmentation as a radiologist would pick them, and
// fits the SOFA liver template to them by plastic strains (seed 002), writing the fitted meshes, a picture
// of the fit over the scan and reports. Each step is the same code as its own command.
#include "cmd_fit.h"
#include "cmd_markers.h"
#include "common.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/viz/slice_overlay.h"

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace vesalius::cli {

namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_DATA_DIR;

struct DemoOptions {
  std::string scan = kData + "/ct-abdomen-pelvis/example_ct.nii.gz";
  std::string organLabels = kData + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz";
  std::string table = kData + "/ct-abdomen-pelvis/labels_total_v1.tsv";
  std::string organ = "liver";
  std::string templ = kData + "/liver/liver.obj";
  std::string smoothTemplate = kData + "/liver/liver-smooth.obj";
  int markers = 300;
  int refits = 3;
  long targetTets = 5000;
  std::string out = "demo-output";
  CommonOptions common;
};

struct SegmentOutcome {
  double bodyMl = 0, boneMl = 0, subcutaneousFatMl = 0;
};

std::string in(const DemoOptions& o, const std::string& name) { return (fs::path(o.out) / name).string(); }

void writeSurface(const DemoOptions& o, const std::string& name, const TriMesh& mesh, double voxelMl,
                  const std::string& what, io::Report& report) {
  const std::string path = in(o, name + ".vtp");
  io::writeTriMesh(path, mesh, io::MeshWriteOptions{o.common.writeOptions()});
  report.output(name, path);
  const io::TriMeshSummary summary = io::summarize(mesh);
  report.metric(name, {{"triangles", summary.triangles},
                       {"closed", summary.closed},
                       {"components", summary.components},
                       {"self_intersections", summary.selfIntersections},
                       {"surface_volume_ml", summary.volume.value_or(0.0) / 1000.0},
                       {"voxel_volume_ml", voxelMl}});
  std::cout << "  " << path << "  (" << what << ", " << mesh.F.rows() << " triangles, "
            << (summary.closed ? "closed" : "open") << ", " << voxelMl << " ml)\n";
}

double volumeMl(const segmentation::Mask& mask) {
  return double(segmentation::countVoxels(mask)) * mask.geometry.spacing.prod() / 1000.0;
}

// The skin label is a shell one or two voxels thick, too thin to carry a smooth surface of its own; the
// skin surface users want is the outer boundary of the body, so the body is meshed instead.
SegmentOutcome writeSurfaces(const DemoOptions& o, const Image& scan, const LabelMap& labels, io::Report& report,
                             Progress& progress) {
  auto timer = report.time("surfaces");
  SegmentOutcome outcome;
  const segmentation::Mask body = segmentation::segmentCtBody(scan, segmentation::CtTissueOptions{});
  outcome.bodyMl = volumeMl(body);
  writeSurface(o, "body", meshing::labelSurface(segmentation::labelMapOf(body, {1, "body"}), 1), outcome.bodyMl,
               "skin surface", report);
  const std::vector<Label> tissues = {segmentation::kCtSubcutaneousFat, segmentation::kCtFat,
                                      segmentation::kCtSoftTissue, segmentation::kCtBone};
  for (const meshing::LabelSurface& s : meshing::labelSurfaces(labels, tissues, {}, &progress)) {
    const double ml = volumeMl(segmentation::maskOf(labels.labels, s.id));
    if (s.id == segmentation::kCtBone) outcome.boneMl = ml;
    if (s.id == segmentation::kCtSubcutaneousFat) outcome.subcutaneousFatMl = ml;
    writeSurface(o, s.name, s.mesh, ml, "surface", report);
  }
  return outcome;
}

// The organ step: markers where a radiologist would pick them, then the template fitted to them.
FitOutcome fitOrgan(const DemoOptions& o) {
  std::cout << "\nFitting the " << o.organ << " template " << o.templ << " to " << o.markers
            << " ICP markers on the " << o.organ << " label of " << o.organLabels << '\n';
  SampleOptions sample;
  sample.labels = o.organLabels;
  sample.table = o.table;
  sample.label = o.organ;
  sample.count = o.markers;
  sample.out = in(o, o.organ + "_icp.mrk.json");
  sample.common.progress = o.common.progress;
  sample.common.force = o.common.force;
  runSample(sample);

  FitCommandOptions fit;
  fit.templ = o.templ;
  fit.icp = sample.out;
  fit.unattached = true;
  fit.targetTets = o.targetTets;
  fit.refit.refits = o.refits;
  fit.out = in(o, o.organ + "_fitted.vtu");
  fit.surfaceOut = in(o, o.organ + "_fitted.vtp");
  if (!o.smoothTemplate.empty()) {
    fit.embed = o.smoothTemplate;
    fit.embedOut = in(o, o.organ + "_smooth_fitted.obj");
  }
  fit.overlay = o.scan;
  fit.png = in(o, o.organ + "_fit.png");
  fit.common = o.common;
  fit.common.report = in(o, o.organ + "_fit.json");
  return runFit(fit);
}

std::string mm(double value) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(2) << value << " mm";
  return text.str();
}

void printSummary(const DemoOptions& o, const SegmentOutcome& seg, const FitOutcome& fit) {
  std::cout << std::fixed << std::setprecision(0) << "\nSummary\n"
            << "  segmented: body " << seg.bodyMl << " ml, bone " << seg.boneMl << " ml, subcutaneous fat "
            << seg.subcutaneousFatMl << " ml (labels.png)\n"
            << "  fitted " << o.organ << " (" << fit.tets << " tets): marker error mean " << mm(fit.icpBefore.mean())
            << " -> " << mm(fit.icpAfter.mean()) << ", max " << mm(fit.icpBefore.maxCoeff()) << " -> "
            << mm(fit.icpAfter.maxCoeff()) << std::setprecision(0) << " in " << fit.seconds << " s ("
            << o.organ << "_fit.png)\n"
            << "  outputs in " << fs::absolute(o.out).string() << ", stage times and numbers in report.json\n";
}

void runDemo(DemoOptions o) {
  fs::create_directories(o.out);
  io::Report report("demo");
  report.input("scan", o.scan);
  Progress progress(o.common.progressStyle());
  std::cout << "Vesalius demo: segmenting " << o.scan << '\n';

  const Image scan = io::readScan(o.scan);
  LabelMap labels;
  {
    auto timer = report.time("segment");
    labels = segmentation::segmentCtTissues(scan, segmentation::CtTissueOptions{}, &progress);
  }
  std::cout << "Outputs in " << fs::absolute(o.out).string() << ":\n";
  io::writeLabelMap(in(o, "labels.nii.gz"), labels, o.common.writeOptions());
  report.output("labels", in(o, "labels.nii.gz"));
  std::cout << "  " << in(o, "labels.nii.gz") << "  (label map, table in labels.tsv)\n";
  const SegmentOutcome segmented = writeSurfaces(o, scan, labels, report, progress);
  viz::OverlayOptions overlay;
  overlay.write = o.common.writeOptions();
  viz::writeSliceOverlayPng(scan, labels, in(o, "labels.png"), overlay);
  report.output("png", in(o, "labels.png"));
  std::cout << "  " << in(o, "labels.png") << "  (labels over axial, coronal and sagittal slices)\n";
  FitOutcome fitted;
  {
    auto timer = report.time("fit " + o.organ);
    fitted = fitOrgan(o);
  }
  report.metric("fit", {{"organ", o.organ},
                        {"tets", fitted.tets},
                        {"markers", fitted.icpAfter.size()},
                        {"mean_error_before_mm", fitted.icpBefore.mean()},
                        {"mean_error_after_mm", fitted.icpAfter.mean()},
                        {"max_error_after_mm", fitted.icpAfter.maxCoeff()}});
  report.output("fit_report", in(o, o.organ + "_fit.json"));
  report.write(in(o, "report.json"), o.common.writeOptions());
  o.common.finish(report);
  printSummary(o, segmented, fitted);
}

}  // namespace

void addDemoCommand(CLI::App& app) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* cmd = app.add_subcommand("demo", "Run the main job on the shipped example CT: segment it, fit the liver template");
  cmd->add_option("--scan", o->scan, "CT scan to use instead of the shipped one")->capture_default_str();
  cmd->add_option("--organ-labels", o->organLabels, "Organ label map of that scan, on the scan's grid")
      ->capture_default_str();
  cmd->add_option("--table", o->table, "Label table of the organ label map")->capture_default_str();
  cmd->add_option("--organ", o->organ, "Label (name or id) the template is fitted to")->capture_default_str();
  cmd->add_option("--template", o->templ, "Template surface or tet mesh of that organ")->capture_default_str();
  cmd->add_option("--smooth-template", o->smoothTemplate,
                  "Finer surface in the template's space carried by the fit (empty for none)")
      ->capture_default_str();
  cmd->add_option("--markers", o->markers, "ICP markers spread over the organ's boundary")
      ->check(CLI::Range(10, 10000))
      ->capture_default_str();
  cmd->add_option("--target-tets", o->targetTets, "About this many tets for the template")
      ->check(CLI::Range(100L, 1000000L))
      ->capture_default_str();
  cmd->add_option("--refits", o->refits, "Refits of the fit from the fitted shape (vesalius fit --refits)")
      ->check(CLI::Range(0, 20))
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer("Example:\n  vesalius demo --out demo-output --force\n"
              "Takes about 5 minutes on 2 cores: the segmentation, then the liver fit (vesalius fit).");
  cmd->callback([o] { runDemo(*o); });
}

}  // namespace vesalius::cli
