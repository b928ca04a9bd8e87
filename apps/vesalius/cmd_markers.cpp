// vesalius markers: marker files. `sample` spreads ICP markers evenly over a label's boundary (stand-ins for
// a radiologist's picks, seed 002 §3.1, §4.1.1); `suggest` proposes ICP markers where a scan has an edge
// near a roughly placed template (issue 5; docs/methods/marker-suggestions.md); `convert` moves markers
// between 3D Slicer (.mrk.json, .fcsv), plain CSV and ITK-SNAP (.annot) files.
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fit/affine_icp.h"
#include "vesalius/fit/initial_placement.h"
#include "vesalius/fit/smooth_displacement.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/segmentation/normal_edges.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numeric>
#include <optional>

namespace vesalius::cli {

namespace {

struct SampleOptions {
  std::string labels, table, label, out;
  int count = 100;
  std::uint64_t seed = 1;
  CommonOptions common;
};


struct ConvertOptions {
  std::string in, out, scan, kind = "landmark";
  CommonOptions common;
};

MarkerKind parseKind(const std::string& k) {
  if (k == "icp") return MarkerKind::IcpMarker;
  if (k == "attachment") return MarkerKind::Attachment;
  return MarkerKind::Landmark;
}

void runConvert(const ConvertOptions& o) {
  std::optional<GridGeometry> geometry;
  if (!o.scan.empty()) geometry = io::describeScan(o.scan).geometry;
  const GridGeometry* g = geometry ? &*geometry : nullptr;
  const MarkerSet set = io::readMarkers(o.in, io::MarkerReadOptions{parseKind(o.kind), g});
  io::writeMarkers(o.out, set, o.common.writeOptions(), g);
  io::Report report("markers convert");
  report.input("markers", o.in);
  report.output("markers", o.out);
  report.metric("markers", set.markers.size());
  o.common.finish(report);
  std::size_t unplaced = 0;
  for (const Marker& m : set.markers) unplaced += !hasPosition(m.status);
  std::cout << o.out << ": " << set.markers.size() << " markers (LPS)";
  if (unplaced > 0) std::cout << ", " << unplaced << " without a position (undefined or missing)";
  std::cout << "\n";
  const std::vector<std::string> lost = io::markerFieldsNotKept(o.out, set);
  if (!lost.empty()) {
    std::cout << "not kept by " << fileExtension(o.out) << ":";
    for (std::size_t i = 0; i < lost.size(); ++i) std::cout << (i ? ", " : " ") << lost[i];
    std::cout << "\n";
  }
}

void addConvert(CLI::App& markers) {
  auto o = std::make_shared<ConvertOptions>();
  CLI::App* cmd = markers.add_subcommand("convert", "Convert a marker file; the output format follows the extension");
  cmd->add_option("in", o->in, "Input: .mrk.json, .fcsv, .csv or .annot")->required();
  cmd->add_option("--out", o->out, "Output: .mrk.json, .fcsv, .csv or .annot")->required();
  cmd->add_option("--scan", o->scan, "Scan the markers belong to (needed for ITK-SNAP .annot voxel coordinates)");
  cmd->add_option("--kind", o->kind, "Kind of markers whose file does not say")
      ->check(CLI::IsMember({"landmark", "icp", "attachment"}))
      ->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer("Examples:\n  vesalius markers convert picked.fcsv --out picked.mrk.json\n"
              "  vesalius markers convert landmarks.annot --scan ct.nii.gz --out landmarks.mrk.json\n"
              "Statuses (defined, undefined, preview, missing), ids, associated nodes, ITK-SNAP colours and tags\n"
              "are carried where the output format has a place for them; the command says what it has not.");
  cmd->callback([o] { runConvert(*o); });
}

// The smallest distance between two rows of P: a sweep along x over the rows sorted by x.
double minSpacing(const MatrixX3d& P) {
  std::vector<Eigen::Index> order(std::size_t(P.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return P(a, 0) < P(b, 0); });
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && P(order[j], 0) - P(order[i], 0) < best; ++j)
      best = std::min(best, (P.row(order[i]) - P.row(order[j])).norm());
  return best;
}

std::string millimetres(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f mm", value);
  return text;
}

void runSample(const SampleOptions& o) {
  // Refuse an existing output before the work, not after it (writeMarkers checks again when it writes).
  if (!o.common.force && std::filesystem::exists(o.out))
    throw UsageError(o.out + ": exists; pass --force to replace it");
  if (!io::isMarkerFile(o.out))
    throw UsageError(o.out + ": unknown marker file type (use .mrk.json, .fcsv, .csv or .annot)");
  io::Report report("markers sample");
  report.input("labels", o.labels);
  report.parameter("label", o.label);
  report.parameter("count", o.count);
  report.parameter("seed", o.seed);
  const LabelMap map = io::readLabelMap(o.labels, o.table);
  const Label id = resolveLabel(map, o.label, o.labels);
  const LabelEntry* entry = map.table.find(id);
  const std::string name = entry ? entry->name : std::to_string(id);
  const std::string named = "label '" + name + "'" + (entry ? " (" + std::to_string(id) + ")" : "");

  // The surface `vesalius surface` makes (default options), less the cap that closes a label cut by the
  // edge of the scan: that is the scan's edge, not the organ's boundary.
  Progress progress(o.common.progressStyle());
  std::vector<meshing::LabelSurface> surfaces;
  {
    auto timer = report.time("surface");
    surfaces = meshing::labelSurfaces(map, {id}, {}, &progress);
  }
  if (surfaces.empty()) throw BadInput(o.labels, named + " has no voxels");
  const TriMesh& surface = surfaces.front().mesh;
  const TriMesh boundary = meshing::withinScan(surface, map.labels.geometry);
  const double area = triangleAreas(boundary.V, boundary.F).sum(),
               edgeArea = triangleAreas(surface.V, surface.F).sum() - area;
  if (boundary.F.rows() == 0)
    throw BadInput(o.labels, named + " lies wholly on the edge of the scan: no boundary to mark");

  MatrixX3d points;
  {
    auto timer = report.time("spread markers");
    points = meshing::spreadSurfacePoints(boundary, o.count, o.seed);
  }
  MarkerSet set;
  set.name = name;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    Marker m;
    m.label = "icp-" + std::to_string(i + 1);
    m.kind = MarkerKind::IcpMarker;
    m.position = points.row(i).transpose();
    m.description = "on label " + name;
    set.markers.push_back(std::move(m));
  }
  io::writeMarkers(o.out, set, o.common.writeOptions(), &map.labels.geometry);

  const double spacing = minSpacing(points), ideal = std::sqrt(area / double(o.count));
  report.output("markers", o.out);
  report.metric("markers", set.markers.size());
  report.metric("surface_area_mm2", area);
  report.metric("scan_edge_area_mm2", edgeArea);
  report.metric("min_spacing_mm", spacing);
  report.metric("ideal_spacing_mm", ideal);
  o.common.finish(report);
  std::cout << o.out << ": " << set.markers.size() << " ICP markers on " << named << ", LPS mm; closest pair "
            << millimetres(spacing) << " apart, sqrt(area / count) " << millimetres(ideal) << "\n";
  if (edgeArea > 0)
    std::cout << "left out " << std::lround(edgeArea) << " of " << std::lround(area + edgeArea)
              << " mm^2 of surface where the label is cut by the edge of the scan\n";
}

void addSample(CLI::App& markers) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* cmd = markers.add_subcommand(
      "sample", "ICP markers spread evenly over a label's boundary (stand-ins for a radiologist's picks)");
  cmd->add_option("--labels", o->labels, "Label map (NIfTI, NRRD, MetaImage)")->required();
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd->add_option("--label", o->label, "Label id or name whose boundary gets the markers")->required();
  cmd->add_option("--count", o->count, "Number of markers")->check(CLI::Range(1, 10000))->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed: the same seed gives the same markers on every platform")
      ->capture_default_str();
  cmd->add_option("--out", o->out, "Marker file: .mrk.json (3D Slicer), .fcsv, .csv or .annot")->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius markers sample --labels seg.nii.gz --table labels_total_v1.tsv --label liver "
      "--count 150 --seed 7 --out liver_icp.mrk.json\n"
      "Markers lie on the surface `vesalius surface` makes of the label, except where the label is cut by\n"
      "the edge of the scan; they are chosen by farthest-point sampling from 32 random points per marker.");
  cmd->callback([o] { runSample(*o); });
}

struct SuggestOptions {
  std::string scan, templ, labels, table, label, markers, out, placedOut;
  int count = 100, candidatesPerSuggestion = 8, icpPoints = 500, rounds = 4, roundPoints = 1000;
  double searchMm = 8.0, finalSearchMm = 3.0, sigmaMm = 2.0, smoothness = 1.0;
  std::string polarity = "auto";
  std::uint64_t seed = 1;
  CommonOptions common;
};

// The template's surface with triangles facing outward (the edge search needs inside and outside).
TriMesh readTemplateSurface(const std::string& path) {
  TriMesh surface = io::readTriMesh(path);
  if (surface.F.rows() == 0) throw BadInput(path, "has no triangles");
  const long open = countEdges(surface.F).boundary;
  if (open > 0)
    throw BadInput(path, "open surface (" + std::to_string(open) + " boundary edges): its inside is unknown");
  const double volume = enclosedVolume(surface.V, surface.F);
  if (!(std::abs(volume) > 0)) throw BadInput(path, "encloses no volume: its inside and outside are unknown");
  if (volume < 0) surface.F.col(1).swap(surface.F.col(2));
  return surface;
}

// Scan points the template is placed on by similarity ICP: points spread over the label's boundary, or
// the defined markers of a file.
MatrixX3d placementTargets(const SuggestOptions& o, io::Report& report) {
  if (!o.markers.empty()) {
    report.input("markers", o.markers);
    const MarkerSet set = io::readMarkers(o.markers, io::MarkerReadOptions{MarkerKind::IcpMarker});
    std::vector<Eigen::Vector3d> points;
    for (const Marker& m : set.markers)
      if (m.status == MarkerStatus::Defined) points.push_back(m.position);
    if (points.size() < 3) throw BadInput(o.markers, "needs at least 3 defined markers to place the template");
    MatrixX3d P(Eigen::Index(points.size()), 3);
    for (std::size_t i = 0; i < points.size(); ++i) P.row(Eigen::Index(i)) = points[i].transpose();
    return P;
  }
  report.input("labels", o.labels);
  report.parameter("label", o.label);
  const LabelMap map = io::readLabelMap(o.labels, o.table);
  const Label id = resolveLabel(map, o.label, o.labels);
  const std::vector<meshing::LabelSurface> surfaces = meshing::labelSurfaces(map, {id});
  if (surfaces.empty()) throw BadInput(o.labels, "label '" + o.label + "' has no voxels");
  const TriMesh boundary = meshing::withinScan(surfaces.front().mesh, map.labels.geometry);
  if (boundary.F.rows() == 0) throw BadInput(o.labels, "label '" + o.label + "' lies wholly on the scan's edge");
  return meshing::spreadSurfacePoints(boundary, o.icpPoints, o.seed);
}

// Outward unit normals of `surface` at points on it: the normal of the closest triangle.
MatrixX3d normalsAt(const TriMesh& surface, const MatrixX3d& points) {
  const TriangleTree tree(surface.V, surface.F);
  const std::vector<ClosestPoint> closest = tree.closest(points);
  MatrixX3d N(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3i f = surface.F.row(closest[std::size_t(i)].face).transpose();
    const Eigen::Vector3d a = surface.V.row(f[0]), b = surface.V.row(f[1]), c = surface.V.row(f[2]);
    N.row(i) = (b - a).cross(c - a).normalized().transpose();
  }
  return N;
}

// Up to `count` found edges, most confident first, each at least `spacing` mm from those kept before it
// (so a stretch of strong edge does not take every suggestion); then, if fewer were kept, the most
// confident of the rest.
std::vector<std::size_t> pickSpread(const std::vector<segmentation::NormalEdge>& edges, int count, double spacing) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (edges[i].found) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return edges[a].confidence > edges[b].confidence; });
  std::vector<std::size_t> kept, rest;
  for (std::size_t i : order) {
    const bool apart = std::all_of(kept.begin(), kept.end(), [&](std::size_t k) {
      return (edges[i].position - edges[k].position).norm() >= spacing;
    });
    (apart && int(kept.size()) < count ? kept : rest).push_back(i);
  }
  for (std::size_t i = 0; i < rest.size() && int(kept.size()) < count; ++i) kept.push_back(rest[i]);
  return kept;
}

segmentation::EdgePolarity parsePolarity(const std::string& p) {
  if (p == "falling") return segmentation::EdgePolarity::Falling;
  if (p == "rising") return segmentation::EdgePolarity::Rising;
  if (p == "either") return segmentation::EdgePolarity::Either;
  return segmentation::EdgePolarity::Auto;
}

const char* polarityName(segmentation::EdgePolarity p) {
  switch (p) {
    case segmentation::EdgePolarity::Falling: return "falling";
    case segmentation::EdgePolarity::Rising: return "rising";
    case segmentation::EdgePolarity::Either: return "either";
    default: return "auto";
  }
}

MarkerSet suggestionMarkers(const std::vector<segmentation::NormalEdge>& edges, const std::vector<std::size_t>& kept,
                            const std::string& name) {
  MarkerSet set;
  set.name = name;
  for (std::size_t i : kept) {
    const segmentation::NormalEdge& e = edges[i];
    Marker m;
    m.label = "suggested-" + std::to_string(set.markers.size() + 1);
    m.kind = MarkerKind::IcpMarker;
    m.status = MarkerStatus::Preview;  // a proposal until a radiologist accepts it
    m.position = e.position;
    char text[128];
    std::snprintf(text, sizeof text, "confidence %.3f; edge %.1f per mm, %.1f mm from the (bent) template",
                  e.confidence, e.strength, std::abs(e.offsetMm));
    m.description = text;
    set.markers.push_back(std::move(m));
  }
  return set;
}

void checkSuggestOptions(const SuggestOptions& o) {
  for (const std::string& out : {o.out, o.placedOut})
    if (!out.empty() && !o.common.force && std::filesystem::exists(out))
      throw UsageError(out + ": exists; pass --force to replace it");
  const bool annot = o.out.size() >= 6 && o.out.compare(o.out.size() - 6, 6, ".annot") == 0;
  if (!io::isMarkerFile(o.out) || annot)  // ITK-SNAP annotations have no preview status
    throw UsageError(o.out + ": suggestions are written as .mrk.json, .fcsv or .csv");
  if (o.labels.empty() == o.markers.empty()) throw UsageError("give either --labels with --label, or --markers");
  if (!o.labels.empty() && o.label.empty()) throw UsageError("--labels needs --label");
}

void reportSuggestions(io::Report& report, const SuggestOptions& o, const fit::Placement& placement,
                       const segmentation::NormalEdges& found, const std::vector<std::size_t>& kept) {
  double confidence = 0, moved = 0;
  for (std::size_t i : kept) {
    confidence += found.edges[i].confidence;
    moved += std::abs(found.edges[i].offsetMm);
  }
  const double n = std::max<double>(1, double(kept.size()));
  const long edges = std::count_if(found.edges.begin(), found.edges.end(), [](const auto& e) { return e.found; });
  report.output("markers", o.out);
  if (!o.placedOut.empty()) report.output("placed_template", o.placedOut);
  report.parameter("polarity", o.polarity);
  report.metric("similarity_placement_rms_mm", placement.rmsError);
  report.metric("placement_scale", placement.transform.scale);
  report.metric("candidates", found.edges.size());
  report.metric("candidates_with_edge", edges);
  report.metric("polarity", polarityName(found.polarity));
  report.metric("suggestions", kept.size());
  report.metric("mean_confidence", confidence / n);
  report.metric("mean_moved_mm", moved / n);
  o.common.finish(report);
  std::cout << o.out << ": " << kept.size() << " suggested ICP markers (status preview, LPS mm) from " << edges
            << " of " << found.edges.size() << " candidates with a " << polarityName(found.polarity)
            << " edge; similarity placement RMS " << millimetres(placement.rmsError)
            << " before affine ICP, mean confidence " << confidence / n << ", mean move " << millimetres(moved / n)
            << "\n";
  if (int(kept.size()) < o.count)
    std::cout << "fewer than --count " << o.count << ": the scan has an edge with the organ's tissue inside at only "
              << edges << " candidates\n";
}

// Edges along the normals of `placed` at `count` points spread over its part within the scan.
struct Search {
  MatrixX3d candidates;
  segmentation::NormalEdges found;
  double area = 0;  // mm², of the placed surface within the scan
};

Search searchEdges(const Image& scan, const TriMesh& placed, int count, double searchMm, const SuggestOptions& o) {
  const TriMesh inScan = meshing::withinScan(placed, scan.geometry);
  if (inScan.F.rows() == 0) throw BadInput(o.templ, "placed on the scan, no triangle lies within it");
  Search s;
  s.candidates = meshing::spreadSurfacePoints(inScan, count, o.seed);
  s.found = segmentation::findNormalEdges(scan, s.candidates, normalsAt(placed, s.candidates),
                                          {o.sigmaMm, searchMm, 0.25, parsePolarity(o.polarity)});
  s.area = triangleAreas(inScan.V, inScan.F).sum();
  return s;
}

// Active-shape-model rounds (Cootes et al. 1995 §4): search for edges, bend the template onto them by a
// smooth displacement weighted by their confidence, search again nearer; the search shrinks geometrically
// from --search-mm to --final-search-mm, which the last search (the suggestions') uses.
TriMesh bendOntoEdges(const Image& scan, TriMesh placed, const SuggestOptions& o) {
  for (int r = 0; r < o.rounds; ++r) {
    const double searchMm = o.searchMm * std::pow(o.finalSearchMm / o.searchMm, double(r) / o.rounds);
    const Search s = searchEdges(scan, placed, o.roundPoints, searchMm, o);
    MatrixX3d moves(s.candidates.rows(), 3);
    Eigen::VectorXd weights(s.candidates.rows());
    for (Eigen::Index i = 0; i < s.candidates.rows(); ++i) {
      const segmentation::NormalEdge& e = s.found.edges[std::size_t(i)];
      moves.row(i) = (e.position - s.candidates.row(i).transpose()).transpose();
      weights[i] = e.found ? e.confidence : 0.0;
    }
    placed.V += fit::smoothDisplacement(placed, s.candidates, moves, weights, {o.smoothness});
  }
  return placed;
}

// Places the template, bends it onto the scan's edges, searches once more, writes the suggestions and the
// report.
void runSuggest(const SuggestOptions& o) {
  checkSuggestOptions(o);
  io::Report report("markers suggest");
  report.input("scan", o.scan);
  report.input("template", o.templ);
  report.parameter("count", o.count);
  report.parameter("search_mm", o.searchMm);
  report.parameter("final_search_mm", o.finalSearchMm);
  report.parameter("rounds", o.rounds);
  report.parameter("smoothness", o.smoothness);
  report.parameter("sigma_mm", o.sigmaMm);
  report.parameter("seed", o.seed);
  const TriMesh templ = readTemplateSurface(o.templ);
  const Image scan = io::readScan(o.scan);
  fit::Placement placement;
  TriMesh placed = templ;
  {
    auto timer = report.time("placement");
    const MatrixX3d targets = placementTargets(o, report);
    placement = fit::placeTemplate(templ, MatrixX3d(0, 3), MatrixX3d(0, 3), targets);
    placed.V = placement.transform.apply(templ.V);
    placed = fit::refineAffineIcp(placed, targets);
  }
  Search last;
  {
    auto timer = report.time("bending and edge search");
    placed = bendOntoEdges(scan, placed, o);
    last = searchEdges(scan, placed, o.count * o.candidatesPerSuggestion,
                       o.rounds > 0 ? o.finalSearchMm : o.searchMm, o);
  }
  const std::vector<std::size_t> kept = pickSpread(last.found.edges, o.count, 0.5 * std::sqrt(last.area / o.count));
  const MarkerSet set = suggestionMarkers(last.found.edges, kept, std::filesystem::path(o.templ).stem().string());
  io::writeMarkers(o.out, set, o.common.writeOptions(), &scan.geometry);
  if (!o.placedOut.empty()) io::writeTriMesh(o.placedOut, placed, io::MeshWriteOptions{o.common.writeOptions()});
  reportSuggestions(report, o, placement, last.found, kept);
}

void addSuggest(CLI::App& markers) {
  auto o = std::make_shared<SuggestOptions>();
  CLI::App* cmd = markers.add_subcommand(
      "suggest", "ICP markers proposed where the scan has an edge near a roughly placed template (status preview)");
  cmd->add_option("--scan", o->scan, "Scan (NIfTI, NRRD, MetaImage, DICOM)")->required();
  cmd->add_option("--template", o->templ, "Template surface (closed mesh: .obj, .stl, .ply, .vtk, .vtp), any frame")
      ->required();
  cmd->add_option("--labels", o->labels, "Label map to place the template on (similarity ICP to a label's boundary)");
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd->add_option("--label", o->label, "Label id or name the template is placed on");
  cmd->add_option("--markers", o->markers, "Rough markers on the organ to place the template on, instead of labels");
  cmd->add_option("--out", o->out, "Suggestions: .mrk.json (3D Slicer), .fcsv or .csv (status preview)")
      ->required();
  cmd->add_option("--count", o->count, "Number of suggestions")->check(CLI::Range(1, 2000))->capture_default_str();
  cmd->add_option("--search-mm", o->searchMm, "Search for an edge this far along each normal, both ways (first round)")
      ->check(CLI::Range(0.5, 50.0))->capture_default_str();
  cmd->add_option("--final-search-mm", o->finalSearchMm, "Search distance of the last round, after bending")
      ->check(CLI::Range(0.5, 50.0))->capture_default_str();
  cmd->add_option("--rounds", o->rounds, "Rounds of edge search and bending the template onto the edges")
      ->check(CLI::Range(0, 20))->capture_default_str();
  cmd->add_option("--smoothness", o->smoothness, "Stiffness of the bending (membrane weight per point weight)")
      ->check(CLI::Range(1e-3, 1e3))->capture_default_str();
  cmd->add_option("--sigma-mm", o->sigmaMm, "Gaussian blur before differentiating, mm")
      ->check(CLI::Range(0.1, 10.0))->capture_default_str();
  cmd->add_option("--polarity", o->polarity, "Intensity change from inside to outside the organ at its edge")
      ->check(CLI::IsMember({"auto", "falling", "rising", "either"}))->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed of the candidate points")->capture_default_str();
  cmd->add_option("--placed-out", o->placedOut,
                  "Also write the template surface as placed and bent onto the edges (an overlay for the picker)");
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example:\n  vesalius markers suggest --scan ct.nii.gz --template liver.obj --labels seg.nii.gz "
      "--table labels_total_v1.tsv --label liver --out liver_suggested.mrk.json --count 100\n"
      "The template is placed by similarity then affine ICP, then bent onto the scan's edges in --rounds rounds of\n"
      "edge search (from --search-mm down to --final-search-mm) and smooth displacement; candidates spread over it\n"
      "move along their normals to the strongest edge within --final-search-mm with the organ's tissue inside; the\n"
      "most confident, spread out, are kept. Each point's description gives its confidence (0..1). See\n"
      "docs/methods/marker-suggestions.md.");
  cmd->callback([o] { runSuggest(*o); });
}

}  // namespace

void addMarkersCommand(CLI::App& app) {
  CLI::App* markers =
      app.add_subcommand(
      "markers", "Marker files: ICP markers sampled on a label's boundary, suggested on a scan, format conversion");
  markers->require_subcommand(1);
  addSample(*markers);
  addSuggest(*markers);
  addConvert(*markers);
}

}  // namespace vesalius::cli
