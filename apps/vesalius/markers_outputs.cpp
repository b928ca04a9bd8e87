#include "markers_outputs.h"

#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <numeric>
#include <vector>

namespace vesalius::cli {

namespace {

namespace seg = segmentation;

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

const char* polarityName(seg::EdgePolarity p) {
  switch (p) {
    case seg::EdgePolarity::Falling: return "falling";
    case seg::EdgePolarity::Rising: return "rising";
    case seg::EdgePolarity::Either: return "either";
    default: return "auto";
  }
}

MarkerSet suggestionMarkers(const std::vector<seg::NormalEdge>& edges, const std::vector<std::size_t>& kept,
                            const std::string& name) {
  MarkerSet set;
  set.name = name;
  for (std::size_t i : kept) {
    const seg::NormalEdge& e = edges[i];
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

}  // namespace

void writeSampledMarkers(const std::string& out, const MatrixX3d& points, const SampledBoundary& boundary, int count,
                         const GridGeometry& scan, const CommonOptions& common, io::Report& report) {
  MarkerSet set;
  set.name = boundary.name;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    Marker m;
    m.label = "icp-" + std::to_string(i + 1);
    m.kind = MarkerKind::IcpMarker;
    m.position = points.row(i).transpose();
    m.description = "on label " + boundary.name;
    set.markers.push_back(std::move(m));
  }
  io::writeMarkers(out, set, common.writeOptions(), &scan);

  const double area = boundary.area, edgeArea = boundary.edgeArea;
  const double spacing = minSpacing(points), ideal = std::sqrt(area / double(count));
  report.output("markers", out);
  report.metric("markers", set.markers.size());
  report.metric("surface_area_mm2", area);
  report.metric("scan_edge_area_mm2", edgeArea);
  report.metric("min_spacing_mm", spacing);
  report.metric("ideal_spacing_mm", ideal);
  std::cout << out << ": " << set.markers.size() << " ICP markers on " << boundary.named
            << ", LPS mm; closest pair " << millimetres(spacing) << " apart, sqrt(area / count) "
            << millimetres(ideal) << "\n";
  if (edgeArea > 0)
    std::cout << "left out " << std::lround(edgeArea) << " of " << std::lround(area + edgeArea)
              << " mm^2 of surface where the label is cut by the edge of the scan\n";
}

void writeSuggestions(const patient::MarkerSuggestions& suggested, const SuggestOutputs& o, const GridGeometry& scan,
                      const CommonOptions& common, io::Report& report) {
  const std::vector<std::size_t>& kept = suggested.kept;
  const seg::NormalEdges& found = suggested.found;
  const MarkerSet set = suggestionMarkers(found.edges, kept, std::filesystem::path(o.templ).stem().string());
  io::writeMarkers(o.out, set, common.writeOptions(), &scan);
  if (!o.placedOut.empty())
    io::writeTriMesh(o.placedOut, suggested.placed, io::MeshWriteOptions{common.writeOptions()});

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
  report.metric("similarity_placement_rms_mm", suggested.placement.rmsError);
  report.metric("placement_scale", suggested.placement.transform.scale);
  report.metric("candidates", found.edges.size());
  report.metric("candidates_with_edge", edges);
  report.metric("polarity", polarityName(found.polarity));
  report.metric("suggestions", kept.size());
  report.metric("mean_confidence", confidence / n);
  report.metric("mean_moved_mm", moved / n);
  std::cout << o.out << ": " << kept.size() << " suggested ICP markers (status preview, LPS mm) from " << edges
            << " of " << found.edges.size() << " candidates with a " << polarityName(found.polarity)
            << " edge; similarity placement RMS " << millimetres(suggested.placement.rmsError)
            << " before affine ICP, mean confidence " << confidence / n << ", mean move " << millimetres(moved / n)
            << "\n";
  if (int(kept.size()) < o.count)
    std::cout << "fewer than --count " << o.count << ": the scan has an edge with the organ's tissue inside at only "
              << edges << " candidates\n";
}

void writeConvertedMarkers(const std::string& in, const std::string& out, const MarkerSet& set,
                           const GridGeometry* geometry, const CommonOptions& common, io::Report& report) {
  io::writeMarkers(out, set, common.writeOptions(), geometry);
  report.input("markers", in);
  report.output("markers", out);
  report.metric("markers", set.markers.size());
  std::size_t unplaced = 0;
  for (const Marker& m : set.markers) unplaced += !hasPosition(m.status);
  std::cout << out << ": " << set.markers.size() << " markers (LPS)";
  if (unplaced > 0) std::cout << ", " << unplaced << " without a position (undefined or missing)";
  std::cout << "\n";
  const std::vector<std::string> lost = io::markerFieldsNotKept(out, set);
  if (!lost.empty()) {
    std::cout << "not kept by " << fileExtension(out) << ":";
    for (std::size_t i = 0; i < lost.size(); ++i) std::cout << (i ? ", " : " ") << lost[i];
    std::cout << "\n";
  }
}

}  // namespace vesalius::cli
