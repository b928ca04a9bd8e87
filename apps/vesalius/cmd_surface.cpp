// vesalius surface: closed surfaces of labels, one mesh per label.
#include "command_runner.h"
#include "common.h"
#include "label_map_input.h"

#include "vesalius/core/error.h"
#include "vesalius/core/safe_file_name.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/shared_label_surfaces.h"

#include <algorithm>
#include <filesystem>
#include <iostream>

namespace vesalius::cli {

namespace {

struct SurfaceOptions {
  std::string labels, grid, table, out, format = ".vtp";
  std::vector<std::string> selected;
  int smoothIterations = -1;  // -1: each method's default
  int targetFaces = 0;
  bool shared = false;
  std::string touching;  // --touching: only where each chosen label meets this one
  CommonOptions common;
};

std::string labelName(const LabelMap& map, Label id) {
  const LabelEntry* entry = map.table.find(id);
  return entry ? entry->name : std::to_string(id);
}

meshing::SharedLabelSurfaces makeShared(const LabelMap& map, const std::vector<Label>& ids, const SurfaceOptions& o,
                                        io::Report& report, Progress& progress) {
  meshing::SharedSurfaceOptions options;
  if (o.smoothIterations >= 0) options.smoothingIterations = o.smoothIterations;
  const meshing::SharedLabelSurfaces shared = meshing::sharedLabelSurfaces(map, ids, options, &progress);
  report.metric("repaired_voxels", shared.repairedVoxels);
  return shared;
}

// Touching labels share their triangles (SurfaceNets); one mesh per label all the same.
std::vector<meshing::LabelSurface> sharedSurfaces(const LabelMap& map, const std::vector<Label>& ids,
                                                  const SurfaceOptions& o, io::Report& report, Progress& progress) {
  const meshing::SharedLabelSurfaces shared = makeShared(map, ids, o, report, progress);
  std::vector<meshing::LabelSurface> surfaces;
  for (Label id : shared.ids) surfaces.push_back({id, labelName(map, id), meshing::surfaceOfLabel(shared, id)});
  return surfaces;
}

// --touching: each chosen label's interface with the other label, from the shared surfaces of them all (a
// muscle's insertion on a bone, Wang et al. 2021, §4.1.2). A chosen label that does not touch it is refused.
std::vector<meshing::LabelSurface> interfaceSurfaces(const LabelMap& map, std::vector<Label> ids,
                                                     const SurfaceOptions& o, io::Report& report, Progress& progress) {
  const Label other = resolveLabel(map, o.touching, o.labels);
  if (std::find(ids.begin(), ids.end(), other) != ids.end())
    throw UsageError("surface: --touching " + o.touching + " is also a --label");
  const std::vector<Label> chosen = ids;
  ids.push_back(other);
  const meshing::SharedLabelSurfaces shared = makeShared(map, ids, o, report, progress);
  if (!std::binary_search(shared.ids.begin(), shared.ids.end(), other))
    throw BadInput(o.labels, "label '" + o.touching + "' has no voxels");
  std::vector<meshing::LabelSurface> surfaces;
  for (Label id : chosen) {
    if (!std::binary_search(shared.ids.begin(), shared.ids.end(), id))
      throw BadInput(o.labels, "label '" + labelName(map, id) + "' has no voxels");
    TriMesh mesh = meshing::interfaceOfLabels(shared, id, other);
    if (mesh.F.rows() == 0)
      throw BadInput(o.labels, "label '" + labelName(map, id) + "' does not touch label '" + o.touching + "'");
    surfaces.push_back({id, labelName(map, id), std::move(mesh)});
  }
  return surfaces;
}

void runSurface(const SurfaceOptions& o, CommandRun& run) {
  run.report.input("labels", o.labels);
  run.report.parameter("smooth_iterations", o.smoothIterations >= 0 ? o.smoothIterations
                                            : o.shared ? meshing::SharedSurfaceOptions{}.smoothingIterations
                                                       : meshing::SurfaceOptions{}.smoothingIterations);
  run.report.parameter("target_faces", o.targetFaces);
  run.report.parameter("shared", o.shared);
  run.report.parameter("touching", o.touching);
  if (o.shared && o.targetFaces > 0) throw UsageError("surface: --target-faces cannot keep --shared boundaries shared");
  if (!o.touching.empty() && !o.shared) throw UsageError("surface: --touching needs --shared");
  if (!o.touching.empty() && o.selected.empty()) throw UsageError("surface: --touching needs at least one --label");
  const LabelMap map = readLabelsOption(o.labels, o.table, o.grid, run.report);

  std::vector<Label> ids;
  for (const std::string& s : o.selected) ids.push_back(resolveLabel(map, s, o.labels));
  // One label goes to --out as a file; several go into --out as a folder, one file per label name, written
  // whole or not at all (core/atomic_file.h). Its path is checked before the work.
  const bool single = ids.size() == 1;
  if (!single) checkOutputFolder(o.out, o.common.writeOptions());

  meshing::SurfaceOptions options;
  if (o.smoothIterations >= 0) options.smoothingIterations = o.smoothIterations;
  options.targetFaces = o.targetFaces;
  std::vector<meshing::LabelSurface> surfaces;
  {
    auto timer = run.report.time("surfaces");
    surfaces = !o.touching.empty() ? interfaceSurfaces(map, ids, o, run.report, run.progress)
               : o.shared          ? sharedSurfaces(map, ids, o, run.report, run.progress)
                                   : meshing::labelSurfaces(map, ids, options, &run.progress);
  }
  if (single) {
    const meshing::LabelSurface& s = surfaces.front();
    io::writeTriMesh(o.out, s.mesh, io::MeshWriteOptions{o.common.writeOptions()});
    run.report.output(s.name, o.out);
    std::cout << o.out << ": " << s.mesh.V.rows() << " vertices, " << s.mesh.F.rows() << " triangles\n";
    return;
  }
  // Label names come from the label table, a file: made safe, so that no name writes outside --out.
  std::vector<std::string> files;
  for (const meshing::LabelSurface& s : surfaces) {
    files.push_back(safeFileName(s.name) + o.format);
    for (std::size_t other = 0; other + 1 < files.size(); ++other)
      if (files[other] == files.back())
        throw BadInput(o.labels, "labels '" + surfaces[other].name + "' and '" + s.name + "' would both be written to " +
                                     files.back() + "; rename one in the label table");
  }
  writeFolderAtomically(o.out, o.common.writeOptions(), [&](const std::string& staging) {
    for (std::size_t i = 0; i < surfaces.size(); ++i) io::writeTriMesh(staging + "/" + files[i], surfaces[i].mesh);
  });
  for (std::size_t i = 0; i < surfaces.size(); ++i) {
    const meshing::LabelSurface& s = surfaces[i];
    const std::string path = (std::filesystem::path(o.out) / files[i]).string();
    run.report.output(s.name, path);
    std::cout << path << ": " << s.mesh.V.rows() << " vertices, " << s.mesh.F.rows() << " triangles\n";
  }
}

}  // namespace

void addSurfaceCommand(CLI::App& app) {
  auto o = std::make_shared<SurfaceOptions>();
  CLI::App* cmd = app.add_subcommand("surface", "Closed, smoothed surfaces of labels (one mesh per label, LPS mm)");
  addLabelsOption(*cmd, o->labels, o->grid, kLabelsHelp)->required();
  slicerParameter(
      cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map"),
      SlicerKind::File, false, ".tsv,.ctbl,.txt");
  cmd->add_option("--label", o->selected, "Label id or name, repeatable (default: every label in the table)");
  // In Slicer one model: the mesh of one --label.
  slicerParameter(cmd->add_option("--out", o->out, "Mesh file for one label; a folder for several")->required(),
                  SlicerKind::Geometry, true, ".vtp,.vtk,.stl,.obj,.ply");
  cmd->add_option("--format", o->format, "File type for several labels")
      ->check(CLI::IsMember({".vtp", ".stl", ".obj", ".ply", ".vtk"}))
      ->capture_default_str();
  cmd->add_option("--smooth", o->smoothIterations,
                  "Smoothing iterations: windowed sinc (default 20; 0: none, else at least 2), or with --shared "
                  "Taubin pairs (default 16)");
  cmd->add_option("--target-faces", o->targetFaces, "Decimate to about this many triangles (0: keep all)");
  cmd->add_flag("--shared", o->shared,
                "Touching labels share their boundary triangles (SurfaceNets; --smooth counts its passes)");
  cmd->add_option("--touching", o->touching,
                  "With --shared: only the part of each --label's surface where it touches this label (id or "
                  "name), an open surface oriented out of the --label (a muscle's insertion on a bone)");
  addCommonOptions(*cmd, o->common);
  cmd->footer("Examples:\n  vesalius surface --labels labels.nii.gz --label liver --out liver.stl\n"
              "  vesalius surface --labels seg.nii.gz --label hip_left --label femur_left --shared --out hip/\n"
              "  vesalius surface --labels seg.nii.gz --label hip_left --shared --touching gluteus_medius_left "
              "--out insertion.vtp");
  cmd->callback([o] { runCommand("surface", o->common, [&](CommandRun& run) { runSurface(*o, run); }); });
}

}  // namespace vesalius::cli
