// vesalius markers: marker files. `sample` spreads ICP markers evenly over a label's boundary (stand-ins for
// a radiologist's picks, seed 002 §3.1, §4.1.1); `convert` moves markers between 3D Slicer (.mrk.json,
// .fcsv), plain CSV and ITK-SNAP (.annot) files.
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"

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
  std::cout << o.out << ": " << set.markers.size() << " markers (LPS)\n";
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
              "  vesalius markers convert landmarks.annot --scan ct.nii.gz --out landmarks.mrk.json");
  cmd->callback([o] { runConvert(*o); });
}

struct SampleOptions {
  std::string labels, table, label, out;
  int count = 100;
  std::uint64_t seed = 1;
  CommonOptions common;
};

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

}  // namespace

void addMarkersCommand(CLI::App& app) {
  CLI::App* markers =
      app.add_subcommand("markers", "Marker files: ICP markers sampled on a label's boundary, format conversion");
  markers->require_subcommand(1);
  addSample(*markers);
  addConvert(*markers);
}

}  // namespace vesalius::cli
