// vesalius markers: marker-file helpers. `convert` moves markers between 3D Slicer (.mrk.json, .fcsv),
// plain CSV and ITK-SNAP (.annot) files.
#include "common.h"

#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"

#include <iostream>
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

}  // namespace

void addMarkersCommand(CLI::App& app) {
  CLI::App* markers = app.add_subcommand("markers", "Marker files: convert between formats");
  markers->require_subcommand(1);
  addConvert(*markers);
}

}  // namespace vesalius::cli
