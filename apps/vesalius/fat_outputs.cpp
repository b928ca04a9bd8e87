#include "fat_outputs.h"

#include "vesalius/core/error.h"
#include "vesalius/fat/thickness_at_vertices.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/viz/rgb_image.h"
#include "vesalius/viz/slice_overlay.h"
#include "vesalius/viz/surface_render.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace vesalius::cli {

namespace {

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

Stats stats(const Eigen::VectorXd& v) { return stats(std::vector<double>(v.data(), v.data() + v.size())); }

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

}  // namespace

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


void writeForestOutputs(const LoadedForest& l, const std::string& out, const std::string& png,
                        const WriteOptions& write, io::Report& report) {
  const fat::FatForest& forest = *l.forest;
  const fat::FatForest::Statistics& fs = forest.statistics();
  Image thickness(forest.geometry(), 0.0f);
  thickness.values = forest.thickness().values;
  thickness.fileType = PixelType::Float32;
  io::writeScan(out, thickness, write);
  report.output("thickness", out);

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
  std::cout << out << ": fat thickness on " << fs.skinVoxels << " skin voxels; where fat lies under the skin ("
            << sCovered.count << "): median " << sCovered.median << " mm, 5-95 % " << sCovered.p05 << "-"
            << sCovered.p95 << " mm, max " << sCovered.max << " mm\n"
            << "forest: " << fs.reachedFatVoxels << " of " << fs.fatVoxels << " fat voxels reached from the skin in "
            << fs.seconds << " s (" << std::llround(rate) << " voxels/s)\n";

  if (!png.empty()) {
    writeThicknessPng(png, l.map, l.fat, forest, sCovered.p95, write);
    report.output("png", png);
  }
}

void writeThicknessOnSurface(const std::string& surface, const std::string& outMesh, const fat::FatForest& forest,
                             double vertexRadiusMm, const WriteOptions& write, io::Report& report) {
  TriMesh mesh = io::readTriMesh(surface);
  fat::VertexThicknessOptions options;
  options.radiusMm = vertexRadiusMm;
  fat::VertexThickness t;
  {
    auto timer = report.time("thickness at vertices");
    t = fat::thicknessAtVertices(forest, mesh.V, mesh.F, options);
  }
  mesh.vertexAttributes.real["fat_thickness"] = t.thickness;
  mesh.vertexAttributes.integer["fat_thickness_source"] = t.source;  // 1 measured, 2 filled, 0 none
  io::writeTriMesh(outMesh, mesh, io::MeshWriteOptions{write});
  report.output("mesh", outMesh);
  const Stats s = stats(t.thickness);
  report.metric("vertex_thickness", toJson(s));
  report.metric("vertices", {{"measured", t.measured}, {"filled", t.filled}, {"unreached", t.unreached}});
  std::cout << outMesh << ": fat_thickness at " << mesh.V.rows() << " vertices (" << t.measured << " measured, "
            << t.filled << " filled from neighbours, " << t.unreached << " unreached), median " << s.median
            << " mm\n";
}

void writeErodedSkin(const std::string& out, TriMesh mesh, const Eigen::VectorXd& t, const fat::ErodedSkin& e,
                     const WriteOptions& write, io::Report& report) {
  mesh.V = e.V;
  mesh.vertexAttributes.real["fat_thickness"] = t;
  mesh.vertexAttributes.real["erosion_mm"] = e.displacement;
  mesh.vertexAttributes.real["inner_radius_mm"] = e.innerRadius;
  mesh.vertexAttributes.integer["erosion_direction"] = e.directionSource;  // 1 forest path, 2 normal, 0 none
  io::writeTriMesh(out, mesh, io::MeshWriteOptions{write});
  report.output("mesh", out);

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
  std::cout << out << ": " << mesh.V.rows() << " vertices moved inward by mean " << e.meanDisplacement << " mm (max "
            << e.maxDisplacement << " mm): " << e.movedAlongPaths << " along forest paths, " << e.movedAlongNormals
            << " along normals; " << e.limited << " limited by the room inside, " << e.reduced
            << " moved less than their thickness; crossing triangle pairs " << e.selfIntersectionsBefore << " before, "
            << e.selfIntersectionsAfter << " after\n";
  if (e.newSelfIntersections > 0)
    std::cerr << "vesalius: warning: " << e.newSelfIntersections << " pairs of triangles cross after erosion that did "
              << "not before (" << e.repairRounds << " repair rounds)\n";
}

void writeTextureOutputs(const std::string& out, const std::string& png, const TriMesh& mesh,
                         const std::string& skinPath, const Eigen::VectorXd& t, const fat::ThicknessTexture& tex,
                         const WriteOptions& write, io::Report& report) {
  writeTextureImage(out, tex, write);
  report.output("texture", out);
  const Stats s = stats(t);
  if (!png.empty()) {
    writeTexturePng(png, tex, s.p95, write);
    report.output("png", png);
  }
  const Eigen::VectorXd back = fat::sampleTextureAtVertices(tex, mesh, skinPath);
  const Stats roundTrip = stats((back - t).cwiseAbs().eval());
  report.metric("vertex_thickness", toJson(s));
  report.metric("texels", {{"inside", tex.inside}, {"rim", tex.rim}, {"filled", tex.filled},
                           {"overlapping", tex.overlapping}, {"fill_sweeps", tex.sweeps}});
  report.metric("vertex_round_trip_error", toJson(roundTrip));
  std::cout << out << ": " << tex.width << " x " << tex.height << " thickness texture, " << tex.inside
            << " texels inside uv triangles, " << tex.rim << " on their rims, " << tex.filled << " filled ("
            << tex.overlapping << " in overlapping charts); read back at the " << mesh.V.rows()
            << " vertices: median error " << roundTrip.median << " mm, 95 % " << roundTrip.p95 << " mm\n";
}

void writeEditOutputs(const EditOutputs& o, TriMesh skin, const std::string& skinPath, const Eigen::VectorXd& t,
                      const WriteOptions& write, io::Report& report) {
  const Stats s = stats(t);
  if (!o.outMesh.empty()) {
    skin.vertexAttributes.real["fat_thickness"] = t;
    io::writeTriMesh(o.outMesh, skin, io::MeshWriteOptions{write});
    report.output("mesh", o.outMesh);
  }
  if (!o.out.empty()) {
    fat::ThicknessTextureOptions options;
    options.width = options.height = o.size;
    const fat::ThicknessTexture tex = fat::rasterizeThickness(skin, t, options, skinPath);
    writeTextureImage(o.out, tex, write);
    report.output("texture", o.out);
    if (!o.png.empty()) {
      writeTexturePng(o.png, tex, s.max, write);
      report.output("png", o.png);
    }
  }
  if (!o.bodyPng.empty()) {
    writeBodyPng(o.bodyPng, skin, t, s.max, write);
    report.output("body_png", o.bodyPng);
  }
  report.metric("vertex_thickness", toJson(s));
  std::cout << (o.out.empty() ? o.outMesh : o.out) << ": fat from bone amounts at " << skin.V.rows()
            << " skin vertices: median " << s.median << " mm, 5-95 % " << s.p05 << "-" << s.p95 << " mm, max " << s.max
            << " mm\n";
}

}  // namespace vesalius::cli
