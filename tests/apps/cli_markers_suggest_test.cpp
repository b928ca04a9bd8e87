// `vesalius markers suggest` end to end on the test CT: the liver template, placed by similarity and affine
// ICP on TotalSegmentator's liver label and bent onto the scan's edges, gets suggested ICP markers; most lie
// within 2 mm of the label's boundary, more than without the bending and clearly more than points spread
// over the placed template without the edge search (so the search, not the placement, puts them there). Every suggestion is a preview with a confidence in [0, 1]; a missing
// template and an unknown label are refused in one line naming the file.
#include "run_command.h"

#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/surface_samples.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
const std::string kScan = kData + "/ct-abdomen-pelvis/example_ct.nii.gz";
const std::string kLabels = kData + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz";
const std::string kTable = kData + "/ct-abdomen-pelvis/labels_total_v1.tsv";
const std::string kTemplate = kData + "/liver/liver.obj";
constexpr int kCount = 100;

std::string outputPath(const std::string& name) {
  const fs::path dir = fs::path(outputDir()) / "markers_suggest";
  fs::create_directories(dir);
  fs::remove(dir / name);
  return (dir / name).string();
}

CommandResult suggest(const std::string& templ, const std::string& label, const std::string& out,
                      std::vector<std::string> more = {}) {
  std::vector<std::string> args{"markers", "suggest", "--scan", kScan, "--template", templ, "--labels", kLabels,
                                "--table", kTable, "--label", label, "--out", out, "--progress", "none"};
  args.insert(args.end(), more.begin(), more.end());
  return runVesalius(args);
}

// Fraction of the rows of P within `mm` of the liver label's boundary (the surface `vesalius surface`
// makes, less the cap where the scan cuts the liver, as cli_test.cpp's expectFittedLiver).
double fractionNearLiver(const MatrixX3d& P, double mm) {
  const LabelMap organs = io::readLabelMap(kLabels, kTable);
  const Label liver = organs.table.resolve("liver");
  const TriMesh boundary =
      meshing::withinScan(meshing::labelSurfaces(organs, {liver}).front().mesh, organs.labels.geometry);
  const TriangleTree tree(boundary.V, boundary.F);
  long near = 0;
  for (const ClosestPoint& c : tree.closest(P)) near += std::sqrt(c.squaredDistance) <= mm;
  return double(near) / double(P.rows());
}

// "confidence 0.812; ..." as the command writes it into each point's description.
double confidenceOf(const Marker& m) {
  const std::string key = "confidence ";
  EXPECT_EQ(m.description.rfind(key, 0), 0u) << m.description;
  return std::stod(m.description.substr(key.size()));
}

// The defaults (the template bent onto the scan's edges in 4 rounds) against --rounds 0 (one edge search
// from the placed template, the method before the bending) and against points spread over the placed
// template without any edge search.
TEST(CliMarkersSuggest, SuggestionsLieOnTheLiverBoundaryMoreThanThePlacedTemplate) {
  const std::string out = outputPath("liver_suggested.mrk.json"), bentPath = outputPath("liver_bent.vtp"),
                    reportPath = outputPath("suggest.json"), unbentOut = outputPath("liver_unbent.mrk.json"),
                    placedPath = outputPath("liver_placed.vtp");
  const CommandResult r = suggest(
      kTemplate, "liver", out, {"--count", std::to_string(kCount), "--placed-out", bentPath, "--report", reportPath});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out;
  const CommandResult unbent = suggest(kTemplate, "liver", unbentOut,
                                       {"--count", std::to_string(kCount), "--rounds", "0", "--placed-out", placedPath});
  ASSERT_EQ(unbent.exitCode, 0) << unbent.err;

  // Fewer than --count only when too few candidates have an edge with the organ's tissue inside.
  const MarkerSet set = io::readMarkers(out);
  const int n = int(set.markers.size());
  ASSERT_GE(n, kCount * 9 / 10);
  ASSERT_LE(n, kCount);
  MatrixX3d suggested(n, 3);
  for (int i = 0; i < n; ++i) {
    const Marker& m = set.markers[std::size_t(i)];
    EXPECT_EQ(m.status, MarkerStatus::Preview) << m.label;
    EXPECT_EQ(m.kind, MarkerKind::IcpMarker) << m.label;
    const double confidence = confidenceOf(m);
    EXPECT_GE(confidence, 0.0) << m.label;
    EXPECT_LE(confidence, 1.0) << m.label;
    suggested.row(i) = m.position.transpose();
  }
  const MarkerSet unbentSet = io::readMarkers(unbentOut);
  MatrixX3d unbentSuggested(Eigen::Index(unbentSet.markers.size()), 3);
  for (std::size_t i = 0; i < unbentSet.markers.size(); ++i)
    unbentSuggested.row(Eigen::Index(i)) = unbentSet.markers[i].position.transpose();

  // Baseline: as many points spread over the placed template (within the scan, as the candidates are),
  // where they would be without the edge search.
  const TriMesh placed = io::readTriMesh(placedPath);
  const MatrixX3d unmoved =
      meshing::spreadSurfacePoints(meshing::withinScan(placed, io::describeScan(kScan).geometry), kCount, 1);
  const double withSearch = fractionNearLiver(suggested, 2.0), withoutBending = fractionNearLiver(unbentSuggested, 2.0),
               withoutSearch = fractionNearLiver(unmoved, 2.0);
  std::cout << "within 2 mm of the liver label's boundary: " << withSearch << " of the suggestions, "
            << withoutBending << " of those without bending (--rounds 0), " << withoutSearch
            << " of the points on the placed template\n";
  // Measured 0.81, 0.72 and 0.18 (docs/methods/marker-suggestions.md: 0.78-0.84 over seeds 1-4); issue 5
  // aims at 0.9, which edges of the diaphragm and body wall next to the liver keep out of reach.
  EXPECT_GE(withSearch, 0.78) << "suggestions within 2 mm of the liver label's boundary";
  EXPECT_GE(withSearch - withoutBending, 0.06) << "what bending the template onto the edges adds";
  EXPECT_GE(withSearch - withoutSearch, 0.55) << "what the edge search adds to the placed template";

  std::ifstream in(reportPath);
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["metrics"]["suggestions"].get<int>(), n);
  EXPECT_EQ(report["metrics"]["polarity"].get<std::string>(), "falling");  // the liver is brighter than fat and lung
}

TEST(CliMarkersSuggest, BadInputIsRefusedInOneLineNamingTheFile) {
  const std::string out = outputPath("bad.mrk.json");
  const std::string missing = kData + "/liver/no_such_template.obj";
  const CommandResult noTemplate = suggest(missing, "liver", out);
  EXPECT_NE(noTemplate.exitCode, 0);
  expectContains(noTemplate.err, missing);
  EXPECT_EQ(std::count(noTemplate.err.begin(), noTemplate.err.end(), '\n'), 1) << noTemplate.err;

  const CommandResult unknown = suggest(kTemplate, "livr", out);
  EXPECT_NE(unknown.exitCode, 0);
  expectContains(unknown.err, kLabels);
  EXPECT_EQ(std::count(unknown.err.begin(), unknown.err.end(), '\n'), 1) << unknown.err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace vesalius::test
