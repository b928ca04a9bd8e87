// vesalius markers: marker files. `sample` spreads ICP markers evenly over a label's boundary (stand-ins for
// a radiologist's picks, Wang et al. 2021, §3.1, §4.1.1); `suggest` proposes ICP markers where a scan has an edge
// near a roughly placed template (issue 5; docs/methods/marker-suggestions.md); `convert` moves markers
// between 3D Slicer (.mrk.json, .fcsv), plain CSV and ITK-SNAP (.annot) files.
#include "command_runner.h"
#include "common.h"
#include "label_map_input.h"
#include "markers_outputs.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/stage_clock.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_boundary_points.h"
#include "vesalius/patient/marker_suggestions.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <utility>
#include <vector>

namespace vesalius::cli {

namespace {

struct SampleOptions {
  std::string labels, grid, table, label, out;
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

void runConvert(const ConvertOptions& o, CommandRun& run) {
  std::optional<GridGeometry> geometry;
  if (!o.scan.empty()) geometry = io::describeScan(o.scan).geometry;
  const GridGeometry* g = geometry ? &*geometry : nullptr;
  const MarkerSet set = io::readMarkers(o.in, io::MarkerReadOptions{parseKind(o.kind), g});
  writeConvertedMarkers(o.in, o.out, set, g, o.common, run.report);
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
  cmd->callback([o] { runCommand("markers convert", o->common, [&](CommandRun& run) { runConvert(*o, run); }); });
}

void runSample(const SampleOptions& o, CommandRun& run) {
  // Refuse an existing output before the work, not after it (writeMarkers checks again when it writes).
  if (!o.common.force && std::filesystem::exists(o.out))
    throw UsageError(o.out + ": exists; pass --force to replace it");
  if (!io::isMarkerFile(o.out))
    throw UsageError(o.out + ": unknown marker file type (use .mrk.json, .fcsv, .csv or .annot)");
  run.report.input("labels", o.labels);
  run.report.parameter("label", o.label);
  run.report.parameter("count", o.count);
  run.report.parameter("seed", o.seed);
  const LabelMap map = readLabelsOption(o.labels, o.table, o.grid, run.report);
  const Label id = resolveLabel(map, o.label, o.labels);
  const LabelEntry* entry = map.table.find(id);
  const std::string name = entry ? entry->name : std::to_string(id);
  const std::string named = "label '" + name + "'" + (entry ? " (" + std::to_string(id) + ")" : "");
  const meshing::LabelBoundaryPoints spread = meshing::labelBoundaryPoints(map, id, {o.count, o.seed}, &run.progress);
  for (const auto& [stage, seconds] : spread.stageSeconds) run.report.stage(stage, seconds);
  if (!spread.hasVoxels) throw BadInput(o.labels, named + " has no voxels");
  if (spread.points.rows() == 0)
    throw BadInput(o.labels, named + " lies wholly on the edge of the scan: no boundary to mark");
  writeSampledMarkers(o.out, spread.points, {name, named, spread.area, spread.scanEdgeArea}, o.count,
                      map.labels.geometry, o.common, run.report);
}

void addSample(CLI::App& markers) {
  auto o = std::make_shared<SampleOptions>();
  CLI::App* cmd = markers.add_subcommand(
      "sample", "ICP markers spread evenly over a label's boundary (stand-ins for a radiologist's picks)");
  addLabelsOption(*cmd, o->labels, o->grid, kLabelsHelp)->required();
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
  cmd->callback([o] { runCommand("markers sample", o->common, [&](CommandRun& run) { runSample(*o, run); }); });
}

struct SuggestOptions {
  std::string scan, templ, labels, grid, table, label, markers, out, placedOut;
  patient::MarkerSuggestionOptions method;  // all but the polarity and the template's name, from the options
  int icpPoints = 500;
  std::string polarity = "auto";
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
  const LabelMap map = readLabelsOption(o.labels, o.table, o.grid, report);
  const Label id = resolveLabel(map, o.label, o.labels);
  const meshing::LabelBoundaryPoints spread = meshing::labelBoundaryPoints(map, id, {o.icpPoints, o.method.seed});
  if (!spread.hasVoxels) throw BadInput(o.labels, "label '" + o.label + "' has no voxels");
  if (spread.points.rows() == 0) throw BadInput(o.labels, "label '" + o.label + "' lies wholly on the scan's edge");
  return spread.points;
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

segmentation::EdgePolarity parsePolarity(const std::string& p) {
  if (p == "falling") return segmentation::EdgePolarity::Falling;
  if (p == "rising") return segmentation::EdgePolarity::Rising;
  if (p == "either") return segmentation::EdgePolarity::Either;
  return segmentation::EdgePolarity::Auto;
}

// Places the template, bends it onto the scan's edges, searches once more (patient/marker_suggestions.h),
// writes the suggestions and the report.
void runSuggest(const SuggestOptions& o, CommandRun& run) {
  checkSuggestOptions(o);
  run.report.input("scan", o.scan);
  run.report.input("template", o.templ);
  run.report.parameter("count", o.method.count);
  run.report.parameter("search_mm", o.method.searchMm);
  run.report.parameter("final_search_mm", o.method.finalSearchMm);
  run.report.parameter("rounds", o.method.rounds);
  run.report.parameter("smoothness", o.method.smoothness);
  run.report.parameter("sigma_mm", o.method.sigmaMm);
  run.report.parameter("seed", o.method.seed);
  const TriMesh templ = readTemplateSurface(o.templ);
  const Image scan = io::readScan(o.scan);
  std::vector<std::pair<std::string, double>> reading;
  StageClock clock(reading);
  const MatrixX3d targets = placementTargets(o, run.report);
  clock.end("placement");
  patient::MarkerSuggestionOptions options = o.method;
  options.polarity = parsePolarity(o.polarity);
  options.templateName = o.templ;
  const patient::MarkerSuggestions suggested = patient::suggestMarkers(scan, templ, targets, options);
  // Reading the points the template is placed on counts as placement.
  for (const auto& [stage, seconds] : suggested.stageSeconds)
    run.report.stage(stage, seconds + (stage == "placement" ? reading.front().second : 0.0));
  writeSuggestions(suggested, {o.out, o.placedOut, o.templ, o.polarity, o.method.count}, scan.geometry, o.common,
                   run.report);
}

void addSuggest(CLI::App& markers) {
  auto o = std::make_shared<SuggestOptions>();
  CLI::App* cmd = markers.add_subcommand(
      "suggest", "ICP markers proposed where the scan has an edge near a roughly placed template (status preview)");
  cmd->add_option("--scan", o->scan, "Scan (NIfTI, NRRD, MetaImage, DICOM)")->required();
  cmd->add_option("--template", o->templ, "Template surface (closed mesh: .obj, .stl, .ply, .vtk, .vtp), any frame")
      ->required();
  addLabelsOption(*cmd, o->labels, o->grid,
                  "Label map to place the template on (similarity ICP to a label's boundary)");
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  cmd->add_option("--label", o->label, "Label id or name the template is placed on");
  cmd->add_option("--markers", o->markers, "Rough markers on the organ to place the template on, instead of labels");
  cmd->add_option("--out", o->out, "Suggestions: .mrk.json (3D Slicer), .fcsv or .csv (status preview)")
      ->required();
  cmd->add_option("--count", o->method.count, "Number of suggestions")
      ->check(CLI::Range(1, 2000))->capture_default_str();
  cmd->add_option("--search-mm", o->method.searchMm,
                  "Search for an edge this far along each normal, both ways (first round)")
      ->check(CLI::Range(0.5, 50.0))->capture_default_str();
  cmd->add_option("--final-search-mm", o->method.finalSearchMm, "Search distance of the last round, after bending")
      ->check(CLI::Range(0.5, 50.0))->capture_default_str();
  cmd->add_option("--rounds", o->method.rounds, "Rounds of edge search and bending the template onto the edges")
      ->check(CLI::Range(0, 20))->capture_default_str();
  cmd->add_option("--smoothness", o->method.smoothness, "Stiffness of the bending (membrane weight per point weight)")
      ->check(CLI::Range(1e-3, 1e3))->capture_default_str();
  cmd->add_option("--sigma-mm", o->method.sigmaMm, "Gaussian blur before differentiating, mm")
      ->check(CLI::Range(0.1, 10.0))->capture_default_str();
  cmd->add_option("--polarity", o->polarity, "Intensity change from inside to outside the organ at its edge")
      ->check(CLI::IsMember({"auto", "falling", "rising", "either"}))->capture_default_str();
  cmd->add_option("--seed", o->method.seed, "Random seed of the candidate points")->capture_default_str();
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
  cmd->callback([o] { runCommand("markers suggest", o->common, [&](CommandRun& run) { runSuggest(*o, run); }); });
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
