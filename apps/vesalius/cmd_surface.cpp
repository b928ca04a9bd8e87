// vesalius surface: closed surfaces of labels, one mesh per label.
#include "common.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"

#include <filesystem>
#include <iostream>

namespace vesalius::cli {

namespace {

struct SurfaceOptions {
  std::string labels, table, out, format = ".vtp";
  std::vector<std::string> selected;
  int smoothIterations = 20;
  int targetFaces = 0;
  CommonOptions common;
};

void runSurface(const SurfaceOptions& o) {
  io::Report report("surface");
  report.input("labels", o.labels);
  report.parameter("smooth_iterations", o.smoothIterations);
  report.parameter("target_faces", o.targetFaces);
  const LabelMap map = io::readLabelMap(o.labels, o.table);

  std::vector<Label> ids;
  for (const std::string& s : o.selected) ids.push_back(resolveLabel(map, s, o.labels));
  // One label goes to --out as a file; several go into --out as a folder, one file per label name.
  const bool single = ids.size() == 1;
  if (!single) std::filesystem::create_directories(o.out);

  meshing::SurfaceOptions options;
  options.smoothingIterations = o.smoothIterations;
  options.targetFaces = o.targetFaces;
  Progress progress(o.common.progressStyle());
  std::vector<meshing::LabelSurface> surfaces;
  {
    auto timer = report.time("surfaces");
    surfaces = meshing::labelSurfaces(map, ids, options, &progress);
  }
  for (const meshing::LabelSurface& s : surfaces) {
    const std::string path = single ? o.out : (std::filesystem::path(o.out) / (s.name + o.format)).string();
    io::writeTriMesh(path, s.mesh, io::MeshWriteOptions{o.common.writeOptions()});
    report.output(s.name, path);
    std::cout << path << ": " << s.mesh.V.rows() << " vertices, " << s.mesh.F.rows() << " triangles\n";
  }
  o.common.finish(report);
}

}  // namespace

void addSurfaceCommand(CLI::App& app) {
  auto o = std::make_shared<SurfaceOptions>();
  CLI::App* cmd = app.add_subcommand("surface", "Closed, smoothed surfaces of labels (one mesh per label, LPS mm)");
  cmd->add_option("--labels", o->labels, "Label map (NIfTI, NRRD, MetaImage)")->required();
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd->add_option("--label", o->selected, "Label id or name, repeatable (default: every label in the table)");
  cmd->add_option("--out", o->out, "Mesh file for one label; a folder for several")->required();
  cmd->add_option("--format", o->format, "File type for several labels")
      ->check(CLI::IsMember({".vtp", ".stl", ".obj", ".ply", ".vtk"}))
      ->capture_default_str();
  cmd->add_option("--smooth", o->smoothIterations, "Windowed-sinc smoothing iterations (0: none, else at least 2)")
      ->capture_default_str();
  cmd->add_option("--target-faces", o->targetFaces, "Decimate to about this many triangles (0: keep all)");
  addCommonOptions(*cmd, o->common);
  cmd->footer("Example:\n  vesalius surface --labels labels.nii.gz --label liver --out liver.stl");
  cmd->callback([o] { runSurface(*o); });
}

}  // namespace vesalius::cli
