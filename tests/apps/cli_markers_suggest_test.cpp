// `vesalius markers suggest` end to end on the test CT: the liver template, placed by similarity and affine
// ICP on TotalSegmentator's liver label and bent onto the scan's edges, gets suggested ICP markers; most lie
// within 2 mm of the label's boundary (at least 90 %, as issue 5 aims), no fewer than without the bending
// and far more than points spread over the placed template without the edge search (so the search, not
// the placement, puts them there); those on the boundary are not biased in or out, and none of the others
// lies deep inside the liver (each is printed with the labels near it). Every suggestion is a preview with
// a confidence in [0, 1]; a missing template and an unknown label are refused in one line naming the file.
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
#include <set>
#include <string>
#include <vector>

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

// The liver label's boundary (the surface `vesalius surface` makes, less the cap where the scan cuts the
// liver, as cli_test.cpp's expectFittedLiver), oriented outward.
struct LiverBoundary {
  LabelMap organs = io::readLabelMap(kLabels, kTable);
  Label liver = organs.table.resolve("liver");
  TriMesh mesh =
      meshing::withinScan(meshing::labelSurfaces(organs, {liver}).front().mesh, organs.labels.geometry);
  TriangleTree tree{mesh.V, mesh.F};

  // Fraction of the rows of P within `mm` of the boundary.
  double fractionWithin(const MatrixX3d& P, double mm) const {
    long near = 0;
    for (const ClosestPoint& c : tree.closest(P)) near += std::sqrt(c.squaredDistance) <= mm;
    return double(near) / double(P.rows());
  }
  // Distance of each row of P to the boundary, positive outside (by the closest triangle's normal).
  std::vector<double> signedDistances(const MatrixX3d& P) const {
    const std::vector<ClosestPoint> closest = tree.closest(P);
    std::vector<double> d;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const ClosestPoint& c = closest[std::size_t(i)];
      const Eigen::Vector3d a = mesh.V.row(mesh.F(c.face, 0)), b = mesh.V.row(mesh.F(c.face, 1)),
                            e = mesh.V.row(mesh.F(c.face, 2));
      const double side = (P.row(i).transpose() - c.point).dot((b - a).cross(e - a));
      d.push_back(side >= 0 ? std::sqrt(c.squaredDistance) : -std::sqrt(c.squaredDistance));
    }
    return d;
  }
  // The labels other than the liver with a voxel centre within `mm` of `p`, by name.
  std::set<std::string> otherLabelsNear(const Eigen::Vector3d& p, double mm) const {
    const GridGeometry& g = organs.labels.geometry;
    const Eigen::Vector3i centre = g.worldToIndex(p).array().round().cast<int>();
    const Eigen::Vector3i reach = (mm * g.spacing.cwiseInverse()).array().ceil().cast<int>();
    std::set<std::string> names;
    for (int k = centre.z() - reach.z(); k <= centre.z() + reach.z(); ++k)
      for (int j = centre.y() - reach.y(); j <= centre.y() + reach.y(); ++j)
        for (int i = centre.x() - reach.x(); i <= centre.x() + reach.x(); ++i) {
          if (!g.contains(i, j, k) || (g.indexToWorld(Eigen::Vector3d(i, j, k)) - p).norm() > mm) continue;
          const Label l = organs.labels.at(i, j, k);
          if (l == 0 || l == liver) continue;
          names.insert(organs.table.find(l) ? organs.table.find(l)->name : std::to_string(l));
        }
    return names;
  }
};

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
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
  const LiverBoundary liver;
  const double withSearch = liver.fractionWithin(suggested, 2.0),
               withoutBending = liver.fractionWithin(unbentSuggested, 2.0),
               withoutSearch = liver.fractionWithin(unmoved, 2.0);
  std::cout << "within 2 mm of the liver label's boundary: " << withSearch << " of the suggestions, "
            << withoutBending << " of those without bending (--rounds 0), " << withoutSearch
            << " of the points on the placed template\n";
  // What the method is held to (docs/methods/marker-suggestions.md): nine in ten within 2 mm of the organ's
  // boundary. The edge search alone is nearly as good as after bending the template onto the edges; bending
  // must not lose.
  EXPECT_GE(withSearch, 0.90) << "suggestions within 2 mm of the liver label's boundary";
  EXPECT_GE(withSearch, withoutBending) << "bending the template onto the edges loses suggestions";
  EXPECT_GE(withSearch - withoutSearch, 0.55) << "what the edge search adds to the placed template";

  // In or out (docs/methods/marker-suggestions.md, "Where the misses are"): each miss, and the medians.
  const std::vector<double> signedMm = liver.signedDistances(suggested);
  std::vector<double> hits;
  int outside = 0;
  double deepest = 0;
  for (int i = 0; i < n; ++i) {
    const double d = signedMm[std::size_t(i)];
    deepest = std::min(deepest, d);
    if (std::abs(d) <= 2.0) {
      hits.push_back(d);
      continue;
    }
    outside += d > 0;
    std::cout << set.markers[std::size_t(i)].label << " " << d << " mm from the boundary, LPS "
              << suggested.row(i) << ", within 8 mm of:";
    for (const std::string& name : liver.otherLabelsNear(suggested.row(i).transpose(), 8.0))
      std::cout << " " << name;
    std::cout << "\n";
  }
  const double hitMedian = median(hits);
  std::cout << "signed distance (outside positive): median " << median(signedMm) << " mm, of those within 2 mm "
            << hitMedian << " mm; " << outside << " of " << n - int(hits.size()) << " misses outside; deepest "
            << deepest << " mm\n";
  // Measured -0.58 mm: no bias beyond a third of the 3 mm voxel. 5 of 9 misses outside (3 at the right
  // body wall, 7-10 mm out; 10 of 17 before the plateau check, 18 of 19 before the tissue check asked for a
  // step of two deviations), the 4 inside 2.1-2.5 mm in: the liver's own edge, not one deep inside it.
  EXPECT_LE(std::abs(hitMedian), 1.0) << "the suggestions on the boundary are biased in or out";
  EXPECT_LE(outside, 7) << "misses outside the liver (body wall, colon)";
  EXPECT_GE(deepest, -4.0) << "a suggestion deep inside the liver";

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
