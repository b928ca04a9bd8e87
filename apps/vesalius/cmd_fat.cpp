// vesalius fat: subcutaneous fat thickness from segmented skin and fat (seed 000 §5).
//   forest   the forest of shortest paths from the skin through the fat: a thickness image (mm on skin
//            voxels) and, given a skin surface, the thickness at its vertices as a point attribute.
//   erode    the skin surface moved inward by the thickness, along the forest's paths where given.
//   texture  the thickness at a skin surface's vertices rasterized into its uv texture.
//   edit     the fat editor (§6): per-bone fat amounts over bounded biharmonic weights of a reference's
//            bones, as a texture on the reference skin's uv and a picture of the body.
#include "bone_fat_amounts.h"
#include "common.h"
#include "thickness_input.h"

#include "vesalius/core/error.h"
#include "vesalius/fat/erode_skin.h"
#include "vesalius/fat/fat_forest.h"
#include "vesalius/fat/thickness_at_vertices.h"
#include "vesalius/fat/thickness_texture.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/reference_anatomy_io.h"
#include "vesalius/io/text_file.h"
#include "vesalius/segmentation/label_ops.h"
#include "vesalius/viz/rgb_image.h"
#include "vesalius/viz/slice_overlay.h"
#include "vesalius/viz/surface_render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

namespace vesalius::cli {

namespace {

// Where the skin and fat masks come from, and the forest's options (shared by forest, erode, texture).
struct ForestSource {
  std::string labels, table, skinLabel = "skin", fatLabel = "subcutaneous_fat", fatMask;
  double maxDistance = std::numeric_limits<double>::infinity();
  double gatherRadius = -1, vertexRadius = 0;
};

struct ForestOptions {
  ForestSource source;
  std::string out, surface, outMesh, png;
  CommonOptions common;
};

// Fails before any work if an output would replace an input or an existing file without --force.
void checkOutputs(const std::vector<std::string>& outs, const std::vector<std::string>& ins, bool force) {
  namespace fs = std::filesystem;
  for (const std::string& out : outs) {
    if (out.empty()) continue;
    for (const std::string& in : ins)
      if (!in.empty() && fs::exists(in) && fs::exists(out) && fs::equivalent(in, out))
        throw UsageError(out + ": is an input; choose another output");
    if (fs::exists(out) && !force) throw UsageError(out + ": exists (use --force to replace it)");
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

// A viridis-like ramp of eight colours, dark to light, for thickness pictures.
const std::array<viz::Rgb, 8> kRamp{{{{68, 1, 84}}, {{70, 50, 127}}, {{54, 92, 141}}, {{39, 127, 142}},
                                     {{31, 161, 135}}, {{74, 194, 109}}, {{159, 218, 58}}, {{253, 231, 37}}}};

// The thickness over three orthogonal slices (viz/slice_overlay.h): tissues in grey (fat light, other
// labels dark), skin voxels in solid colours by thickness bins of 5 mm or more; the legend is the colour
// bar. Slices pass through the centroid of the skin voxels that have fat under them.
void writeThicknessPng(const std::string& path, const LabelMap& map, const fat::Mask& fatMask,
                       const fat::FatForest& forest, double upper, const WriteOptions& write) {
  // Eight bins of the ramp from 0 to `upper` (the 95th percentile), the last one open.
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
    bins.table.add({Label(b + 1), name.str(), kRamp[b]});
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
  options.radiusMm = o.source.vertexRadius;
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

// The masks and the forest of a ForestSource, with their parameters in the report.
struct LoadedForest {
  LabelMap map;
  fat::Mask skin, fat;
  std::unique_ptr<fat::FatForest> forest;
};

LoadedForest loadForest(const ForestSource& o, io::Report& report, Progress& progress) {
  LoadedForest l;
  report.input("labels", o.labels);
  if (!o.fatMask.empty()) report.input("fat_mask", o.fatMask);
  l.map = io::readLabelMap(o.labels, o.table);
  const Label skinId = resolveLabel(l.map, o.skinLabel, o.labels);
  l.skin = maskOfLabel(l.map, skinId, "skin", o.labels);
  if (o.fatMask.empty()) {
    l.fat = maskOfLabel(l.map, resolveLabel(l.map, o.fatLabel, o.labels), "fat", o.labels);
  } else {
    const LabelMap m = io::readLabelMap(o.fatMask);  // any nonzero voxel is fat
    l.fat = fat::Mask(m.labels.geometry, 0);
    for (std::size_t v = 0; v < l.fat.values.size(); ++v) l.fat.values[v] = m.labels.values[v] != 0;
  }
  report.parameter("skin_label", skinId);
  report.parameter("fat", o.fatMask.empty() ? nlohmann::json(o.fatLabel) : nlohmann::json(o.fatMask));
  report.parameter("max_distance_mm", std::isfinite(o.maxDistance) ? nlohmann::json(o.maxDistance) : nullptr);
  report.parameter("gather_radius_mm", o.gatherRadius);

  fat::FatForestOptions options;
  options.maxDistanceMm = o.maxDistance;
  options.gatherRadiusMm = o.gatherRadius;
  progress.begin("fat forest", "shortest paths from the skin through the fat");
  l.forest = std::make_unique<fat::FatForest>(l.skin, l.fat, options, o.fatMask.empty() ? o.labels : o.fatMask);
  progress.end();
  report.stage("fat forest", l.forest->statistics().seconds);
  return l;
}

void runForest(const ForestOptions& o) {
  if (o.surface.empty() != o.outMesh.empty()) throw UsageError("fat forest: --surface and --out-mesh go together");
  checkOutputs({o.out, o.outMesh, o.png, o.common.report},
               {o.source.labels, o.source.fatMask, o.surface, o.source.table}, o.common.force);
  io::Report report("fat forest");
  if (!o.surface.empty()) report.input("surface", o.surface);
  Progress progress(o.common.progressStyle());
  const LoadedForest l = loadForest(o.source, report, progress);
  const fat::FatForest& forest = *l.forest;
  const fat::FatForest::Statistics& fs = forest.statistics();

  Image thickness(forest.geometry(), 0.0f);
  thickness.values = forest.thickness().values;
  thickness.fileType = PixelType::Float32;
  io::writeScan(o.out, thickness, o.common.writeOptions());
  report.output("thickness", o.out);

  std::vector<double> all, covered;
  for (std::size_t v = 0; v < l.skin.values.size(); ++v) {
    if (!l.skin.values[v]) continue;
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
    writeThicknessPng(o.png, l.map, l.fat, forest, sCovered.p95, o.common.writeOptions());
    report.output("png", o.png);
  }
  if (!o.surface.empty()) runThicknessOnSurface(o, forest, report);
  o.common.finish(report);
}

// --labels and the forest's options, on any subcommand that builds a forest.
void addForestSourceOptions(CLI::App& cmd, ForestSource& o, bool required) {
  auto* labels = cmd.add_option("--labels", o.labels,
                                "Label map with skin and fat classes (e.g. from 'vesalius segment', CT or MRI)");
  if (required) labels->required();
  cmd.add_option("--table", o.table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd.add_option("--skin-label", o.skinLabel, "Skin label id or name")->capture_default_str();
  cmd.add_option("--fat-label", o.fatLabel, "Fat label id or name")->capture_default_str();
  cmd.add_option("--fat-mask", o.fatMask,
                 "Fat from a mask on the same grid instead (any nonzero voxel; e.g. TotalSegmentator's "
                 "subcutaneous_fat.nii.gz)");
  cmd.add_option("--max-distance", o.maxDistance, "Leave fat farther than this from the skin unreached (mm)");
  cmd.add_option("--gather-radius", o.gatherRadius,
                 "A skin voxel takes the largest tree thickness within this radius (mm); -1: one voxel "
                 "diagonal; 0: the paper's per-tree value")
      ->capture_default_str();
  cmd.add_option("--vertex-radius", o.vertexRadius,
                 "Skin voxels within this distance of a vertex give its thickness (mm); 0: one voxel diagonal")
      ->capture_default_str();
}

void addForestCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<ForestOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "forest", "Fat thickness under the skin by a forest of shortest paths from skin voxels through fat (seed 000 §5)");
  addForestSourceOptions(*cmd, o->source, true);
  cmd->add_option("--out", o->out, "Thickness image: float mm on skin voxels, 0 elsewhere (.nii.gz, .nrrd, .mha)")
      ->required();
  cmd->add_option("--surface", o->surface, "Skin surface mesh (LPS mm) to carry the thickness to");
  cmd->add_option("--out-mesh", o->outMesh,
                  "The surface with point attributes fat_thickness (mm) and fat_thickness_source "
                  "(1 measured, 2 filled from neighbours, 0 none); .vtp or .vtk keep them");
  cmd->add_option("--png", o->png, "Picture of the thickness on the skin over three orthogonal slices");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius segment --scan testdata/ct-abdomen-pelvis/example_ct.nii.gz --modality ct --out ct.nii.gz\n"
      "  vesalius surface --labels ct.nii.gz --label skin --out skin.vtp\n"
      "  vesalius fat forest --labels ct.nii.gz --out thickness.nii.gz --surface skin.vtp --out-mesh skin_fat.vtp");
  cmd->callback([o] { runForest(*o); });
}

// Thickness at the skin's vertices from --thickness, else from the forest (thicknessAtVertices).
Eigen::VectorXd vertexThickness(const std::string& spec, const TriMesh& skin, const std::string& skinPath,
                                const LoadedForest& l, const ForestSource& source, io::Report& report) {
  if (!spec.empty()) {
    std::string kind;
    Eigen::VectorXd t = readThickness(spec, skin, skinPath, kind);
    report.parameter("thickness", spec);
    report.parameter("thickness_from", kind);
    return t;
  }
  fat::VertexThicknessOptions options;
  options.radiusMm = source.vertexRadius;
  const fat::VertexThickness t = fat::thicknessAtVertices(*l.forest, skin.V, skin.F, options);
  report.parameter("thickness_from", "forest");
  report.metric("vertices", {{"measured", t.measured}, {"filled", t.filled}, {"unreached", t.unreached}});
  return t.thickness;
}

Stats stats(const Eigen::VectorXd& v) { return stats(std::vector<double>(v.data(), v.data() + v.size())); }

struct ErodeOptions {
  ForestSource source;
  std::string skin, thickness, out;
  double pathRadius = 0, maxFraction = 0.5;
  CommonOptions common;
};

void runErode(const ErodeOptions& o) {
  if (o.thickness.empty() && o.source.labels.empty()) throw UsageError("fat erode: give --thickness, --labels or both");
  checkOutputs({o.out, o.common.report}, {o.skin, o.thickness, o.source.labels, o.source.fatMask, o.source.table},
               o.common.force);
  io::Report report("fat erode");
  report.input("skin", o.skin);
  Progress progress(o.common.progressStyle());
  TriMesh mesh = io::readTriMesh(o.skin);
  LoadedForest l;
  if (!o.source.labels.empty()) l = loadForest(o.source, report, progress);
  const Eigen::VectorXd t = vertexThickness(o.thickness, mesh, o.skin, l, o.source, report);

  fat::ErodeSkinOptions options;
  options.pathRadiusMm = o.pathRadius;
  options.maxFractionOfInnerRadius = o.maxFraction;
  options.source = o.thickness.empty() ? o.source.labels : o.thickness;
  report.parameter("path_radius_mm", o.pathRadius);
  report.parameter("max_fraction_of_inner_radius",
                   std::isfinite(o.maxFraction) ? nlohmann::json(o.maxFraction) : nullptr);
  fat::ErodedSkin e;
  {
    auto timer = report.time("erode");
    progress.begin("erode", "moving the skin inward by the fat thickness");
    e = fat::erodeSkin(mesh.V, mesh.F, t, l.forest.get(), options);
    progress.end();
  }
  mesh.V = e.V;
  mesh.vertexAttributes.real["fat_thickness"] = t;
  mesh.vertexAttributes.real["erosion_mm"] = e.displacement;
  mesh.vertexAttributes.real["inner_radius_mm"] = e.innerRadius;
  mesh.vertexAttributes.integer["erosion_direction"] = e.directionSource;  // 1 forest path, 2 normal, 0 none
  io::writeTriMesh(o.out, mesh, io::MeshWriteOptions{o.common.writeOptions()});
  report.output("mesh", o.out);

  report.metric("thickness", toJson(stats(t)));
  report.metric("displacement", toJson(stats(e.displacement)));
  report.metric("moved_along_paths", e.movedAlongPaths);
  report.metric("moved_along_normals", e.movedAlongNormals);
  report.metric("limited_by_inner_radius", e.limited);
  report.metric("moved_less_than_thickness", e.reduced);
  report.metric("repaired", e.repaired);
  report.metric("repair_rounds", e.repairRounds);
  report.metric("self_intersections", {{"before", e.selfIntersectionsBefore}, {"after", e.selfIntersectionsAfter},
                                       {"new", e.newSelfIntersections}});
  std::cout << o.out << ": " << mesh.V.rows() << " vertices moved inward by mean " << e.meanDisplacement << " mm (max "
            << e.maxDisplacement << " mm): " << e.movedAlongPaths << " along forest paths, " << e.movedAlongNormals
            << " along normals; " << e.limited << " limited by the room inside, " << e.reduced
            << " moved less than their thickness; crossing triangle pairs " << e.selfIntersectionsBefore << " before, "
            << e.selfIntersectionsAfter << " after\n";
  if (e.newSelfIntersections > 0)
    std::cerr << "vesalius: warning: " << e.newSelfIntersections << " pairs of triangles cross after erosion that did "
              << "not before (" << e.repairRounds << " repair rounds)\n";
  o.common.finish(report);
}

void addErodeCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<ErodeOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "erode", "Move a skin surface inward by the fat thickness, along the forest's paths (seed 000 §5, Fig. 2.b)");
  cmd->add_option("--skin", o->skin, "Skin (body) surface mesh, closed, LPS mm")->required();
  cmd->add_option("--thickness", o->thickness,
                  "Fat thickness: a number (mm), a texture image read at the skin's uv (from 'fat texture'), a mesh "
                  "with point attribute fat_thickness, or a text file of one value per vertex; default: from "
                  "the forest of --labels");
  addForestSourceOptions(*cmd, o->source, false);
  cmd->add_option("--out", o->out,
                  "Eroded mesh, same topology, with point attributes fat_thickness, erosion_mm, inner_radius_mm "
                  "and erosion_direction (1 forest path, 2 normal, 0 none); .vtp or .vtk keep them")
      ->required();
  cmd->add_option("--path-radius", o->pathRadius,
                  "Skin voxels within this distance of a vertex offer their forest paths (mm); 0: two voxel diagonals")
      ->capture_default_str();
  cmd->add_option("--max-fraction", o->maxFraction,
                  "A vertex moves at most this fraction of the largest inner ball touching it (0 to 1; inf: no limit)")
      ->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius fat erode --skin body.vtp --labels ct.nii.gz --out eroded.vtp --report erode.json\n"
      "  vesalius fat erode --skin body.obj --thickness 5 --out eroded.obj");
  cmd->callback([o] { runErode(*o); });
}

// The ramp at f in [0, 1], linear between its colours.
viz::Rgb rampColour(double f) {
  const double x = std::clamp(f, 0.0, 1.0) * double(kRamp.size() - 1);
  const std::size_t i = std::min(std::size_t(x), kRamp.size() - 2);
  viz::Rgb c;
  for (int k = 0; k < 3; ++k)
    c[k] = std::uint8_t(std::lround(kRamp[i][k] + (x - double(i)) * (kRamp[i + 1][k] - kRamp[i][k])));
  return c;
}

// The texture as a picture, v up: thickness 0 to `upper` along the ramp, filled texels at half brightness.
void writeTexturePng(const std::string& path, const fat::ThicknessTexture& t, double upper, const WriteOptions& write) {
  viz::RgbImage image(t.width, t.height, {0, 0, 0});
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      viz::Rgb c = rampColour(upper > 0 ? t.at(x, y) / upper : 0.0);
      if (t.coverage[std::size_t(x) + std::size_t(t.width) * y] == fat::ThicknessTexture::kFilled)
        for (auto& channel : c) channel = std::uint8_t(channel / 2);
      image.set(x, t.height - 1 - y, c);
    }
  viz::writePng(path, image, write);
}

// The texture as a float image, W x H x 1; its physical space is the uv square: texel centres at
// ((x + 0.5) / W, (y + 0.5) / H).
void writeTextureImage(const std::string& path, const fat::ThicknessTexture& t, const WriteOptions& write) {
  GridGeometry uvSquare;
  uvSquare.size = Eigen::Vector3i(t.width, t.height, 1);
  uvSquare.spacing = Eigen::Vector3d(1.0 / t.width, 1.0 / t.height, 1);
  uvSquare.origin = Eigen::Vector3d(0.5 / t.width, 0.5 / t.height, 0);
  Image image(uvSquare, 0.0f);
  image.values = t.values;
  image.fileType = PixelType::Float32;
  io::writeScan(path, image, write);
}

struct TextureOptions {
  ForestSource source;
  std::string skin, thickness, out, png;
  int size = 1024;
  CommonOptions common;
};

void runTexture(const TextureOptions& o) {
  if (o.thickness.empty() && o.source.labels.empty()) throw UsageError("fat texture: give --thickness or --labels");
  checkOutputs({o.out, o.png, o.common.report},
               {o.skin, o.thickness, o.source.labels, o.source.fatMask, o.source.table}, o.common.force);
  io::Report report("fat texture");
  report.input("skin", o.skin);
  Progress progress(o.common.progressStyle());
  const TriMesh mesh = io::readTriMesh(o.skin);
  if (mesh.UV.rows() == 0) throw BadInput(o.skin, "the mesh has no texture coordinates (uv)");
  LoadedForest l;
  if (o.thickness.empty()) l = loadForest(o.source, report, progress);
  const Eigen::VectorXd t = vertexThickness(o.thickness, mesh, o.skin, l, o.source, report);

  fat::ThicknessTextureOptions options;
  options.width = options.height = o.size;
  report.parameter("size", o.size);
  fat::ThicknessTexture tex;
  {
    auto timer = report.time("texture");
    progress.begin("texture", "rasterizing the thickness over the uv charts");
    tex = fat::rasterizeThickness(mesh, t, options, o.skin);
    progress.end();
  }
  writeTextureImage(o.out, tex, o.common.writeOptions());
  report.output("texture", o.out);
  const Stats s = stats(t);
  if (!o.png.empty()) {
    writeTexturePng(o.png, tex, s.p95, o.common.writeOptions());
    report.output("png", o.png);
  }
  const Eigen::VectorXd back = fat::sampleTextureAtVertices(tex, mesh, o.skin);
  const Stats roundTrip = stats((back - t).cwiseAbs().eval());
  report.metric("vertex_thickness", toJson(s));
  report.metric("texels", {{"inside", tex.inside}, {"rim", tex.rim}, {"filled", tex.filled},
                           {"overlapping", tex.overlapping}, {"fill_sweeps", tex.sweeps}});
  report.metric("vertex_round_trip_error", toJson(roundTrip));
  std::cout << o.out << ": " << o.size << " x " << o.size << " thickness texture, " << tex.inside
            << " texels inside uv triangles, " << tex.rim << " on their rims, " << tex.filled << " filled ("
            << tex.overlapping << " in overlapping charts); read back at the " << mesh.V.rows()
            << " vertices: median error " << roundTrip.median << " mm, 95 % " << roundTrip.p95 << " mm\n";
  o.common.finish(report);
}

void addTextureCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<TextureOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "texture", "Rasterize the fat thickness at a skin's vertices into its uv texture (seed 000 §5)");
  cmd->add_option("--skin", o->skin, "Skin surface mesh with texture coordinates (.obj, .vtp, .ply), LPS mm")
      ->required();
  cmd->add_option("--thickness", o->thickness,
                  "Fat thickness at the vertices instead of a forest: a number (mm), a mesh with point attribute "
                  "fat_thickness, or a text file of one value per vertex");
  addForestSourceOptions(*cmd, o->source, false);
  cmd->add_option("--size", o->size, "Texture width and height in texels")->capture_default_str()->check(
      CLI::Range(1, 16384));
  cmd->add_option("--out", o->out,
                  "Float texture (.nrrd, .nii.gz, .mha): W x H x 1, thickness in mm; physical space: the uv square")
      ->required();
  cmd->add_option("--png", o->png, "Picture of the texture (v up), filled texels at half brightness");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n"
      "  vesalius fat texture --skin skin_uv.obj --labels ct.nii.gz --size 1024 --out fat.nrrd --png fat.png\n"
      "  vesalius fat erode --skin other_skin_uv.obj --thickness fat.nrrd --out eroded.vtp");
  cmd->callback([o] { runTexture(*o); });
}

// Faces coloured by the mean thickness of their corners: eight layers, one per colour of the ramp from
// 0 to `upper` (the last one open), seen from the front.
void writeBodyPng(const std::string& path, const TriMesh& skin, const Eigen::VectorXd& thickness, double upper,
                  const WriteOptions& write) {
  std::array<std::vector<Eigen::Index>, kRamp.size()> faces;
  for (Eigen::Index f = 0; f < skin.F.rows(); ++f) {
    const double t = (thickness[skin.F(f, 0)] + thickness[skin.F(f, 1)] + thickness[skin.F(f, 2)]) / 3;
    const double x = upper > 0 ? t / upper * double(kRamp.size()) : 0.0;
    faces[std::min(kRamp.size() - 1, std::size_t(std::max(0.0, x)))].push_back(f);
  }
  std::vector<TriMesh> meshes;
  std::vector<viz::Rgb> colours;
  for (std::size_t b = 0; b < faces.size(); ++b) {
    if (faces[b].empty()) continue;
    TriMesh m;
    m.V = skin.V;
    m.F.resize(Eigen::Index(faces[b].size()), 3);
    for (std::size_t i = 0; i < faces[b].size(); ++i) m.F.row(Eigen::Index(i)) = skin.F.row(faces[b][i]);
    meshes.push_back(std::move(m));
    colours.push_back(kRamp[b]);
  }
  std::vector<viz::SurfaceLayer> layers;
  for (std::size_t l = 0; l < meshes.size(); ++l) layers.push_back({&meshes[l], colours[l], 1.0});
  viz::SurfaceRenderOptions options;
  options.write = write;
  viz::writeSurfacesPng(layers, path, options);
}

struct EditOptions {
  std::string reference, amounts, out, outMesh, png, bodyPng;
  int size = 1024;
  BoneFatSettings fat;
  CommonOptions common;
};

void runEdit(const EditOptions& o) {
  if (o.out.empty() && o.outMesh.empty()) throw UsageError("fat edit: give --out, --out-mesh or both");
  if (!o.png.empty() && o.out.empty()) throw UsageError("fat edit: --png is a picture of the texture of --out");
  if (!o.bodyPng.empty() && !viz::canRenderSurfaces())
    throw UsageError("fat edit: --body-png needs a display (run under xvfb-run)");
  checkOutputs({o.out, o.outMesh, o.png, o.bodyPng, o.common.report}, {o.amounts}, o.common.force);
  io::Report report("fat edit");
  report.input("reference", o.reference);
  report.input("amounts", o.amounts);
  Progress progress(o.common.progressStyle());
  TriMesh skin;
  Eigen::VectorXd t;
  {
    const ReferenceAnatomy reference = io::readReferenceAnatomy(o.reference);
    progress.begin("bone weights", "bounded biharmonic weights of the bones on a voxel grid");
    t = boneFatAtSkin(reference, o.reference, o.amounts, o.fat, report);
    progress.end();
    skin = reference.skin;
  }
  const Stats s = stats(t);
  if (!o.outMesh.empty()) {
    skin.vertexAttributes.real["fat_thickness"] = t;
    io::writeTriMesh(o.outMesh, skin, io::MeshWriteOptions{o.common.writeOptions()});
    report.output("mesh", o.outMesh);
  }
  if (!o.out.empty()) {
    fat::ThicknessTextureOptions options;
    options.width = options.height = o.size;
    const std::string skinPath = (std::filesystem::path(o.reference) / "skin.obj").string();
    const fat::ThicknessTexture tex = fat::rasterizeThickness(skin, t, options, skinPath);
    writeTextureImage(o.out, tex, o.common.writeOptions());
    report.output("texture", o.out);
    if (!o.png.empty()) {
      writeTexturePng(o.png, tex, s.max, o.common.writeOptions());
      report.output("png", o.png);
    }
  }
  if (!o.bodyPng.empty()) {
    writeBodyPng(o.bodyPng, skin, t, s.max, o.common.writeOptions());
    report.output("body_png", o.bodyPng);
  }
  report.metric("vertex_thickness", toJson(s));
  std::cout << (o.out.empty() ? o.outMesh : o.out) << ": fat from bone amounts at " << skin.V.rows()
            << " skin vertices: median " << s.median << " mm, 5-95 % " << s.p05 << "-" << s.p95 << " mm, max " << s.max
            << " mm\n";
  o.common.finish(report);
}

void addEditCommand(CLI::App& fatCommand) {
  auto o = std::make_shared<EditOptions>();
  CLI::App* cmd = fatCommand.add_subcommand(
      "edit", "Fat editor: per-bone fat amounts over bounded biharmonic weights of a reference's bones (seed 000 §6)");
  cmd->add_option("--reference", o->reference, "Reference anatomy folder (from `vesalius reference`)")->required();
  cmd->add_option("--amounts", o->amounts,
                  "JSON object of bone (group) names and fat amounts, e.g. {\"pelvis\": 0.4, \"torso\": 0}; an amount "
                  "is a fraction of --max-thickness")
      ->required();
  cmd->add_option("--default-amount", o->fat.defaultAmount, "Amount of the bones the file does not name")->capture_default_str();
  cmd->add_option("--max-thickness", o->fat.maxThicknessMm, "Thickness an amount of 1 gives (mm)")->capture_default_str();
  cmd->add_option("--voxel-size", o->fat.voxelSizeMm, "Voxel size of the weights' grid (mm)")->capture_default_str();
  cmd->add_option("--out", o->out,
                  "Float texture on the reference skin's uv (.nrrd, .nii.gz, .mha), W x H x 1, mm; for `transfer --fat`");
  cmd->add_option("--size", o->size, "Texture width and height in texels")->capture_default_str()->check(CLI::Range(1, 16384));
  cmd->add_option("--png", o->png, "Picture of the texture (v up)");
  cmd->add_option("--out-mesh", o->outMesh,
                  "The reference skin with point attribute fat_thickness (mm; .vtp, .vtk); for `transfer --fat` "
                  "when the skin has no uv");
  cmd->add_option("--body-png", o->bodyPng, "Picture of the body coloured by thickness, from the front; needs a display");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  echo '{\"pelvis\": 0.4, \"torso\": 0}' > amounts.json\n"
      "  vesalius fat edit --reference ref --amounts amounts.json --out fat.nrrd --png fat.png --body-png body.png\n"
      "  vesalius transfer --reference ref --target-skin body.obj --fat fat.nrrd --out target\n"
      "Bones are the reference's bone groups (a bone without a group by its name); see docs/methods/fat-thickness.md.");
  cmd->callback([o] { runEdit(*o); });
}

}  // namespace

void addFatCommand(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "fat", "Subcutaneous fat: thickness from segmented skin and fat, erosion, texture (seed 000 §5), editor (§6)");
  cmd->require_subcommand(1);
  addForestCommand(*cmd);
  addErodeCommand(*cmd);
  addTextureCommand(*cmd);
  addEditCommand(*cmd);
}

}  // namespace vesalius::cli
