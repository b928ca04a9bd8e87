// vesalius demo: the main job on the shipped data. Today: segment the example CT into tissue classes,
// write the label map, the skin surface and one closed surface per inner class, a picture of the labels,
// and a report.
#include "common.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/viz/slice_overlay.h"

#include <filesystem>
#include <iostream>

namespace vesalius::cli {

namespace {

namespace fs = std::filesystem;

struct DemoOptions {
  std::string scan = std::string(VESALIUS_DATA_DIR) + "/ct-abdomen-pelvis/example_ct.nii.gz";
  std::string out = "demo-output";
  CommonOptions common;
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
void writeSurfaces(const DemoOptions& o, const Image& scan, const LabelMap& labels, io::Report& report,
                   Progress& progress) {
  auto timer = report.time("surfaces");
  const segmentation::Mask body = segmentation::segmentCtBody(scan, segmentation::CtTissueOptions{});
  writeSurface(o, "body", meshing::labelSurface(segmentation::labelMapOf(body, {1, "body"}), 1), volumeMl(body),
               "skin surface", report);
  const std::vector<Label> tissues = {segmentation::kCtSubcutaneousFat, segmentation::kCtFat,
                                      segmentation::kCtSoftTissue, segmentation::kCtBone};
  for (const meshing::LabelSurface& s : meshing::labelSurfaces(labels, tissues, {}, &progress))
    writeSurface(o, s.name, s.mesh, volumeMl(segmentation::maskOf(labels.labels, s.id)), "surface", report);
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
  writeSurfaces(o, scan, labels, report, progress);
  viz::OverlayOptions overlay;
  overlay.write = o.common.writeOptions();
  viz::writeSliceOverlayPng(scan, labels, in(o, "labels.png"), overlay);
  report.output("png", in(o, "labels.png"));
  std::cout << "  " << in(o, "labels.png") << "  (labels over axial, coronal and sagittal slices)\n";
  report.write(in(o, "report.json"), o.common.writeOptions());
  o.common.finish(report);
  std::cout << "  " << in(o, "report.json") << "  (inputs, stage times)\n";
}

}  // namespace

void addDemoCommand(CLI::App& app) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* cmd = app.add_subcommand("demo", "Run the main job on the shipped example CT");
  cmd->add_option("--scan", o->scan, "CT scan to use instead of the shipped one")->capture_default_str();
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer("Example:\n  vesalius demo --out demo-output --force");
  cmd->callback([o] { runDemo(*o); });
}

}  // namespace vesalius::cli
