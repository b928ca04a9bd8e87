// vesalius tetmesh: a tetrahedral mesh of closed surfaces, or of labels of a label map (one region each).
#include "command_runner.h"
#include "common.h"
#include "label_map_input.h"
#include "vesalius/rigging/label_regions.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/mesh_volume.h"
#include "vesalius/meshing/tet_budget.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/segmentation/label_resample.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace vesalius::cli {

namespace {

struct TetmeshOptions {
  std::vector<std::string> surfaces, selected;
  std::string labels, grid, table, out;
  int body = 0;  // with --labels: label of an outer region, the union of all non-zero voxels (0: none)
  bool shared = false;  // with --labels: touching labels share their boundaries
  meshing::TetrahedralizeOptions tet;
  CommonOptions common;
};

// A surface file's region label: the face label it carries throughout, else its position (1, 2, ...).
std::vector<meshing::RegionSurface> readSurfaces(const TetmeshOptions& o) {
  std::vector<meshing::RegionSurface> regions;
  for (const std::string& path : o.surfaces) {
    TriMesh mesh = io::readTriMesh(path);
    const int position = int(regions.size()) + 1;
    const auto labels = mesh.faceAttributes.integer.find(kLabel);
    const bool uniform = labels != mesh.faceAttributes.integer.end() && labels->second.size() > 0 &&
                         (labels->second.array() == labels->second(0)).all();
    regions.push_back({std::move(mesh), uniform ? labels->second(0) : position, path});
  }
  return regions;
}

// Sujar et al. 2018, §3.2 keeps the image it meshes under 250x700x120 voxels by its choice of voxel size; larger
// maps are resampled (nearest neighbour) onto such a grid.
LabelMap cappedLabels(LabelMap map) {
  const GridGeometry capped =
      segmentation::cappedGeometry(map.labels.geometry, meshing::CoveringGridOptions{}.maxSize);
  if (capped.size == map.labels.geometry.size) return map;
  const Eigen::Vector3i& s = map.labels.geometry.size;
  std::cout << "label map resampled from " << s.x() << "x" << s.y() << "x" << s.z() << " to " << capped.size.x()
            << "x" << capped.size.y() << "x" << capped.size.z() << " voxels (at most 250 L, 120 P, 700 S)\n";
  return segmentation::resampleLabels(map, capped);
}

std::vector<meshing::RegionSurface> labelRegions(const TetmeshOptions& o, CommandRun& run) {
  const LabelMap map = cappedLabels(readLabelsOption(o.labels, o.table, o.grid, run.report));
  std::vector<Label> ids;
  for (const std::string& s : o.selected) ids.push_back(map.table.resolve(s));
  rigging::LabelRegionOptions regions;
  regions.body = o.body;
  return rigging::labelRegionSurfaces(map, ids, regions, o.labels, &run.progress);
}

// --shared: the labels' surfaces share their boundaries where they touch; with --body the rest of the
// body (holes filled) is one more label around them, touching them wherever they reach its surface.
meshing::SharedLabelSurfaces sharedRegions(const TetmeshOptions& o, CommandRun& run) {
  LabelMap map = cappedLabels(readLabelsOption(o.labels, o.table, o.grid, run.report));
  std::vector<Label> ids;
  for (const std::string& s : o.selected) ids.push_back(map.table.resolve(s));
  if (o.body > 0) {
    if (std::find(ids.begin(), ids.end(), Label(o.body)) != ids.end())
      throw UsageError("tetmesh: --body " + std::to_string(o.body) + " is one of the chosen labels");
    std::vector<bool> chosen(65536, ids.empty());
    for (Label id : ids) chosen[id] = true;
    const segmentation::Mask body = segmentation::fillBodyHoles(segmentation::nonZeroMask(map.labels));
    for (std::size_t v = 0; v < body.values.size(); ++v)
      if (body.values[v] && (map.labels.values[v] == 0 || !chosen[map.labels.values[v]]))
        map.labels.values[v] = Label(o.body);
    if (!ids.empty()) ids.push_back(Label(o.body));
  }
  return meshing::sharedLabelSurfaces(map, ids, {}, &run.progress);
}

std::string qualityText(const TetQualityReport& r, const io::TetMeshSummary& s) {
  std::ostringstream out;
  out << std::setprecision(4) << "dihedral angles  min " << r.minDihedral << " deg, max " << r.maxDihedral << " deg\n"
      << "  per 10 deg     ";
  for (long count : r.dihedralHistogram) out << ' ' << count;
  out << "\nradius-edge      max " << r.maxRadiusEdge << ", mean " << r.meanRadiusEdge << "\n"
      << "tet volume       " << r.minVolume << " .. " << r.maxVolume << " mm^3, total " << r.totalVolume << " mm^3\n"
      << "per label        ";
  for (const auto& [label, volume] : s.volumePerLabel)
    out << ' ' << label << ": " << s.tetsPerLabel.at(label) << " tets, " << volume << " mm^3;";
  out << "\ninverted " << r.inverted << ", flat " << r.degenerate << "\n";
  return out.str();
}

void runTetmesh(const TetmeshOptions& o, CommandRun& run) {
  if (o.surfaces.empty() == o.labels.empty()) throw UsageError("tetmesh: give --surface or --labels (not both)");
  if (o.body > 0 && o.labels.empty()) throw UsageError("tetmesh: --body needs --labels");
  if (o.shared && o.labels.empty()) throw UsageError("tetmesh: --shared needs --labels");
  // Said in the options' own names before any file is read; the library checks the same (and, for a
  // volume bound, the tets it needs for what the surfaces enclose against --tet-budget).
  std::ostringstream value;
  if (o.tet.radiusEdge != 0 && !(o.tet.radiusEdge >= meshing::kMinRadiusEdge)) {
    value << o.tet.radiusEdge;
    throw UsageError("tetmesh: --quality must be 0 (no refinement) or at least " + std::to_string(meshing::kMinRadiusEdge).substr(0, 3) +
                     " (below that TetGen may refine for ever), not " + value.str());
  }
  if (!(o.tet.maxVolume >= 0) || !std::isfinite(o.tet.maxVolume)) {
    value << o.tet.maxVolume;
    throw UsageError("tetmesh: --max-volume must be 0 (no bound) or a positive number of mm^3, not " + value.str());
  }
  for (const std::string& s : o.surfaces) run.report.input("surface", s);
  if (!o.labels.empty()) run.report.input("labels", o.labels);
  run.report.parameter("radius_edge", o.tet.radiusEdge);
  run.report.parameter("min_dihedral", o.tet.minDihedral);
  run.report.parameter("max_volume", o.tet.maxVolume);
  run.report.parameter("target_tets", o.tet.targetTets);
  TetMesh mesh;
  std::size_t regionCount = 0;
  if (o.shared) {
    const meshing::SharedLabelSurfaces shared = sharedRegions(o, run);
    run.report.metric("repaired_voxels", shared.repairedVoxels);
    regionCount = shared.ids.size();
    auto timer = run.report.time("tetrahedralize");
    mesh = meshing::tetrahedralizeLabels(shared, o.tet, o.labels);
  } else {
    const auto regions = o.labels.empty() ? readSurfaces(o) : labelRegions(o, run);
    regionCount = regions.size();
    auto timer = run.report.time("tetrahedralize");
    if (regions.size() == 1 && o.tet.targetTets > 0 && !o.tet.keepSurface) {
      // One surface to a tet target: a fine surface is coarsened first so that the target holds.
      meshing::BudgetedTets budgeted = meshing::tetrahedralizeWithinBudget(regions[0].surface, o.tet, regions[0].name);
      mesh = std::move(budgeted.tets);
      mesh.tetAttributes.integer[kLabel].setConstant(regions[0].label);
      run.report.metric("tetrahedralized_faces", budgeted.surfaceFaces);
      if (budgeted.coarsenings > 0)
        std::cout << regions[0].name << ": " << regions[0].surface.F.rows() << " triangles coarsened to "
                  << budgeted.surfaceFaces << " for about " << o.tet.targetTets << " tets\n";
    } else {
      mesh = meshing::tetrahedralizeRegions(regions, o.tet);
    }
  }
  io::writeTetMesh(o.out, mesh, io::MeshWriteOptions{o.common.writeOptions()});
  run.report.output("tets", o.out);
  const TetQualityReport q = tetQualityReport(mesh.V, mesh.T);
  run.report.metric("tets", q.tets);
  run.report.metric("min_dihedral_deg", q.minDihedral);
  run.report.metric("max_radius_edge", q.maxRadiusEdge);
  run.report.metric("inverted", q.inverted);
  std::cout << o.out << ": " << mesh.V.rows() << " vertices, " << mesh.T.rows() << " tetrahedra in "
            << regionCount << " region(s)\n"
            << qualityText(q, io::summarize(mesh));
}

}  // namespace

void addTetmeshCommand(CLI::App& app) {
  auto o = std::make_shared<TetmeshOptions>();
  CLI::App* cmd = app.add_subcommand("tetmesh", "Tetrahedral mesh (TetGen) of closed surfaces or of labels");
  cmd->add_option("--surface", o->surfaces,
                  "Closed surface (.stl .obj .vtp .ply .vtk), repeatable: nested or apart, one region each");
  addLabelsOption(*cmd, o->labels, o->grid, "Label map: one region per label, surfaces as `vesalius surface` makes");
  cmd->add_option("--table", o->table, "Label table for --labels (default: the one beside it)");
  cmd->add_option("--label", o->selected, "Label id or name for --labels, repeatable (default: all in the table)");
  cmd->add_option("--body", o->body,
                  "With --labels: add the union of all labels as an outer region with this label; the chosen "
                  "labels are nested in it (a body with its bones)")
      ->check(CLI::Range(1, 65535));
  cmd->add_flag("--shared", o->shared,
                "With --labels: touching labels share their boundaries (SurfaceNets), so labels may touch "
                "each other and, with --body, the body surface");
  cmd->add_option("--out", o->out, "Tet mesh (.vtu .vtk .msh .mesh .ele); tets carry the cell field 'label'")
      ->required();
  cmd->add_option("--quality", o->tet.radiusEdge, "Largest radius-edge ratio (TetGen -q); 0: no refinement")
      ->capture_default_str();
  cmd->add_option("--min-dihedral", o->tet.minDihedral, "Smallest dihedral angle aimed for, degrees")
      ->capture_default_str();
  cmd->add_option("--max-volume", o->tet.maxVolume, "Largest tet volume, mm^3 (0: no bound)");
  cmd->add_option("--target-tets", o->tet.targetTets,
                  "About this many tets (sets the volume bound; one surface finer than that allows is coarsened "
                  "first, unless --keep-surface)");
  cmd->add_option("--tet-budget", o->tet.maxTets,
                  "Most tets TetGen may make: bounds that need more are refused, a run that reaches it is stopped")
      ->capture_default_str();
  cmd->add_flag("--keep-surface", o->tet.keepSurface, "Add no points on the surfaces (TetGen -Y)");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Examples:\n  vesalius tetmesh --surface liver.stl --out liver.vtu --max-volume 20\n"
      "  vesalius tetmesh --surface body.vtp --surface femur_left.vtp --out body.vtu --target-tets 200000\n"
      "  vesalius tetmesh --labels seg.nii.gz --label hip_left --label hip_right --out hips.vtu\n"
      "  vesalius tetmesh --labels seg.nii.gz --label hip_left --label hip_right --body 1 --out body.vtu\n"
      "  vesalius tetmesh --labels seg.nii.gz --label sacrum --label vertebrae_L5 --shared --out spine.vtu\n"
      "Surfaces must be closed and must not cross (checked first; exit 3 otherwise).");
  cmd->callback([o] { runCommand("tetmesh", o->common, [&](CommandRun& run) { runTetmesh(*o, run); }); });
}

}  // namespace vesalius::cli
