// vesalius fat: subcutaneous fat thickness from segmented skin and fat (seed 000 §5).
//   forest   the forest of shortest paths from the skin through the fat: a thickness image (mm on skin
//            voxels) and, given a skin surface, the thickness at its vertices as a point attribute.
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/fat/fat_forest.h"
#include "vesalius/fat/thickness_at_vertices.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/viz/slice_overlay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>

namespace vesalius::cli {

namespace {

struct ForestOptions {
  std::string labels, table, skinLabel = "skin", fatLabel = "subcutaneous_fat", fatMask;
  std::string out, surface, outMesh, png;
  double maxDistance = std::numeric_limits<double>::infinity();
  double gatherRadius = -1, vertexRadius = 0;
  CommonOptions common;
};

// Fails before any work if an output would replace an input or an existing file without --force.
void checkOutputs(const ForestOptions& o) {
  namespace fs = std::filesystem;
  if (o.surface.empty() != o.outMesh.empty()) throw UsageError("fat forest: --surface and --out-mesh go together");
  for (const std::string& out : {o.out, o.outMesh, o.png, o.common.report}) {
    if (out.empty()) continue;
    for (const std::string& in : {o.labels, o.fatMask, o.surface, o.table})
      if (!in.empty() && fs::exists(in) && fs::exists(out) && fs::equivalent(in, out))
        throw UsageError(out + ": is an input; choose another output");
    if (fs::exists(out) && !o.common.force) throw UsageError(out + ": exists (use --force to replace it)");
  }
}

fat::Mask maskOfLabel(const LabelMap& map, Label id, const std::string& role, const std::string& path) {
  fat::Mask mask = segmentation::maskOf(map.labels, id);
  if (segmentation::countVoxels(mask) == 0)
    throw BadInput(path, "no voxel has the " + role + " label " + std::to_string(id) +
                             (map.table.find(id) ? " (" + map.table.find(id)->name + ")" : std::string()));
  return mask;
}

struct Stats {
  double p05 = 0, median = 0, p95 = 0, max = 0, mean = 0;
  std::int64_t count = 0;
};

Stats stats(std::vector<double> v) {
  Stats s;
  s.count = std::int64_t(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto q = [&](double p) { return v[std::size_t(p * double(v.size() - 1) + 0.5)]; };
  s.p05 = q(0.05), s.median = q(0.5), s.p95 = q(0.95), s.max = v.back();
  for (double x : v) s.mean += x / double(v.size());
  return s;
}

nlohmann::json toJson(const Stats& s) {
  return {{"count", s.count}, {"p05_mm", s.p05}, {"median_mm", s.median}, {"p95_mm", s.p95},
          {"max_mm", s.max}, {"mean_mm", s.mean}};
}

// The thickness over three orthogonal slices (viz/slice_overlay.h): tissues in grey (fat light, other
// labels dark), skin voxels in solid colours by thickness bins of 5 mm or more; the legend is the colour
// bar. Slices pass through the centroid of the skin voxels that have fat under them.
void writeThicknessPng(const std::string& path, const LabelMap& map, const fat::Mask& fatMask,
                       const fat::FatForest& forest, double upper, const WriteOptions& write) {
  // Eight bins of a viridis-like ramp from 0 to `upper` (the 95th percentile), the last one open.
  static const std::array<std::array<std::uint8_t, 3>, 8> ramp{{{{68, 1, 84}}, {{70, 50, 127}}, {{54, 92, 141}},
      {{39, 127, 142}}, {{31, 161, 135}}, {{74, 194, 109}}, {{159, 218, 58}}, {{253, 231, 37}}}};
  const double step = std::max(5.0, 5.0 * std::ceil(upper / 8.0 / 5.0));
  Image grey(map.labels.geometry, 0.0f);
  LabelMap bins{Grid<Label>(map.labels.geometry, 0), {}};
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  double n = 0;
  const GridGeometry& g = map.labels.geometry;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const std::int64_t v = g.linearIndex(i, j, k);
        grey.values[v] = fatMask.values[v] ? 200.0f : (map.labels.values[v] ? 70.0f : 0.0f);
        if (!forest.isSkin(v)) continue;
        const double t = forest.thickness().values[v];
        bins.labels.values[v] = Label(1 + std::min(7, int(t / step)));
        if (t > 0) centroid += Eigen::Vector3d(i, j, k), ++n;
      }
  for (int b = 0; b < 8; ++b) {
    std::ostringstream name;
    name << "fat " << b * step << (b == 7 ? "+ mm" : "-" + std::to_string(int((b + 1) * step)) + " mm");
    bins.table.add({Label(b + 1), name.str(), ramp[b]});
  }
  viz::OverlayOptions options;
  options.window = 255, options.level = 127.5, options.opacity = 1.0, options.outlineOpacity = 1.0;
  if (n > 0) options.voxel = (centroid / n).array().round().cast<int>().matrix();
  options.write = write;
  viz::writeSliceOverlayPng(grey, bins, path, options);
}

void runThicknessOnSurface(const ForestOptions& o, const fat::FatForest& forest, io::Report& report) {
  TriMesh mesh = io::readTriMesh(o.surface);
  fat::VertexThicknessOptions options;
  options.radiusMm = o.vertexRadius;
  fat::VertexThickness t;
  {
    auto timer = report.time("thickness at vertices");
    t = fat::thicknessAtVertices(forest, mesh.V, mesh.F, options);
  }
  mesh.vertexAttributes.real["fat_thickness"] = t.thickness;
  mesh.vertexAttributes.integer["fat_thickness_source"] = t.source;  // 1 measured, 2 filled, 0 none
  io::writeTriMesh(o.outMesh, mesh, io::MeshWriteOptions{o.common.writeOptions()});
  report.output("mesh", o.outMesh);
  const Stats s = stats(std::vector<double>(t.thickness.data(), t.thickness.data() + t.thickness.size()));
  report.metric("vertex_thickness", toJson(s));
  report.metric("vertices", {{"measured", t.measured}, {"filled", t.filled}, {"unreached", t.unreached}});
  std::cout << o.outMesh << ": fat_thickness at " << mesh.V.rows() << " vertices (" << t.measured << " measured, "
            << t.filled << " filled from neighbours, " << t.unreached << " unreached), median " << s.median
            << " mm\n";
}

void runForest(const ForestOptions& o) {
  checkOutputs(o);
  io::Report report("fat forest");
  report.input("labels", o.labels);
  if (!o.fatMask.empty()) report.input("fat_mask", o.fatMask);
  if (!o.surface.empty()) report.input("surface", o.surface);
  Progress progress(o.common.progressStyle());

  const LabelMap map = io::readLabelMap(o.labels, o.table);
  const Label skinId = resolveLabel(map, o.skinLabel, o.labels);
  const fat::Mask skin = maskOfLabel(map, skinId, "skin", o.labels);
  fat::Mask fatMask;
  if (o.fatMask.empty()) {
    fatMask = maskOfLabel(map, resolveLabel(map, o.fatLabel, o.labels), "fat", o.labels);
  } else {
    const LabelMap m = io::readLabelMap(o.fatMask);  // any nonzero voxel is fat
    fatMask = fat::Mask(m.labels.geometry, 0);
    for (std::size_t v = 0; v < fatMask.values.size(); ++v) fatMask.values[v] = m.labels.values[v] != 0;
  }
  report.parameter("skin_label", skinId);
  report.parameter("fat", o.fatMask.empty() ? nlohmann::json(o.fatLabel) : nlohmann::json(o.fatMask));
  report.parameter("max_distance_mm", std::isfinite(o.maxDistance) ? nlohmann::json(o.maxDistance) : nullptr);
  report.parameter("gather_radius_mm", o.gatherRadius);

  fat::FatForestOptions options;
  options.maxDistanceMm = o.maxDistance;
  options.gatherRadiusMm = o.gatherRadius;
  progress.begin("fat forest", "shortest paths from the skin through the fat");
  const fat::FatForest forest(skin, fatMask, options, o.fatMask.empty() ? o.labels : o.fatMask);
  progress.end();
  const fat::FatForest::Statistics& fs = forest.statistics();
  report.stage("fat forest", fs.seconds);

  Image thickness(forest.geometry(), 0.0f);
  thickness.values = forest.thickness().values;
  thickness.fileType = PixelType::Float32;
  io::writeScan(o.out, thickness, o.common.writeOptions());
  report.output("thickness", o.out);

  std::vector<double> all, covered;
  for (std::size_t v = 0; v < skin.values.size(); ++v) {
    if (!skin.values[v]) continue;
    all.push_back(forest.thickness().values[v]);
    if (all.back() > 0) covered.push_back(all.back());
  }
  const Stats sAll = stats(all), sCovered = stats(covered);
  const double rate = fs.seconds > 0 ? double(fs.reachedFatVoxels) / fs.seconds : 0;
  report.metric("skin_voxels", fs.skinVoxels);
  report.metric("fat_voxels", fs.fatVoxels);
  report.metric("reached_fat_voxels", fs.reachedFatVoxels);
  report.metric("skin_voxels_with_fat_tree", fs.skinVoxelsWithFat);
  report.metric("thickness_all_skin", toJson(sAll));
  report.metric("thickness_where_fat", toJson(sCovered));
  report.metric("forest_seconds", fs.seconds);
  report.metric("fat_voxels_per_second", rate);
  std::cout << o.out << ": fat thickness on " << fs.skinVoxels << " skin voxels; where fat lies under the skin ("
            << sCovered.count << "): median " << sCovered.median << " mm, 5-95 % " << sCovered.p05 << "-"
            << sCovered.p95 << " mm, max " << sCovered.max << " mm\n"
            << "forest: " << fs.reachedFatVoxels << " of " << fs.fatVoxels << " fat voxels reached from the skin in "
            << fs.seconds << " s (" << std::llround(rate) << " voxels/s)\n";

  if (!o.png.empty()) {
    writeThicknessPng(o.png, map, fatMask, forest, sCovered.p95, o.common.writeOptions());
    report.output("png", o.png);
  }
  if (!o.surface.empty()) runThicknessOnSurface(o, forest, report);
  o.common.finish(report);
}

void addForestCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<ForestOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "forest", "Fat thickness under the skin by a forest of shortest paths from skin voxels through fat (seed 000 §5)");
  cmd->add_option("--labels", o->labels,
                  "Label map with skin and fat classes (e.g. from 'vesalius segment', CT or MRI)")
      ->required();
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd->add_option("--skin-label", o->skinLabel, "Skin label id or name")->capture_default_str();
  cmd->add_option("--fat-label", o->fatLabel, "Fat label id or name")->capture_default_str();
  cmd->add_option("--fat-mask", o->fatMask,
                  "Fat from a mask on the same grid instead (any nonzero voxel; e.g. TotalSegmentator's "
                  "subcutaneous_fat.nii.gz)");
  cmd->add_option("--out", o->out, "Thickness image: float mm on skin voxels, 0 elsewhere (.nii.gz, .nrrd, .mha)")
      ->required();
  cmd->add_option("--surface", o->surface, "Skin surface mesh (LPS mm) to carry the thickness to");
  cmd->add_option("--out-mesh", o->outMesh,
                  "The surface with point attributes fat_thickness (mm) and fat_thickness_source "
                  "(1 measured, 2 filled from neighbours, 0 none); .vtp or .vtk keep them");
  cmd->add_option("--png", o->png, "Picture of the thickness on the skin over three orthogonal slices");
  cmd->add_option("--max-distance", o->maxDistance, "Leave fat farther than this from the skin unreached (mm)");
  cmd->add_option("--gather-radius", o->gatherRadius,
                  "A skin voxel takes the largest tree thickness within this radius (mm); -1: one voxel "
                  "diagonal; 0: the paper's per-tree value")
      ->capture_default_str();
  cmd->add_option("--vertex-radius", o->vertexRadius,
                  "Skin voxels within this distance of a vertex give its thickness (mm); 0: one voxel diagonal")
      ->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius segment --scan testdata/ct-abdomen-pelvis/example_ct.nii.gz --modality ct --out ct.nii.gz\n"
      "  vesalius surface --labels ct.nii.gz --label skin --out skin.vtp\n"
      "  vesalius fat forest --labels ct.nii.gz --out thickness.nii.gz --surface skin.vtp --out-mesh skin_fat.vtp");
  cmd->callback([o] { runForest(*o); });
}

}  // namespace

void addFatCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("fat", "Subcutaneous fat: thickness from segmented skin and fat (seed 000 §5)");
  cmd->require_subcommand(1);
  addForestCommand(*cmd);
}

}  // namespace vesalius::cli
