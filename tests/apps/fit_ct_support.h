// Shared by the `vesalius fit` tests on the test CT (cli_fit_ct_test, cli_fit_pelvis_test): ICP markers
// sampled on a label's boundary by `vesalius markers sample`, the fit's JSON report, and the measures
// every such test makes: the label's whole boundary against the fitted surface and the label's volume.
#pragma once

#include "run_command.h"
#include "test_data.h"

#include "vesalius/core/markers.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius::test {

// `name` in the test's own folder `dir` under the output directory, made if missing.
inline std::string outputPath(const std::string& dir, const std::string& name) {
  const std::filesystem::path folder = std::filesystem::path(outputDir()) / dir;
  std::filesystem::create_directories(folder);
  return (folder / name).string();
}

inline nlohmann::json readJson(const std::string& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return nlohmann::json::parse(s.str());
}

inline void runOk(const std::vector<std::string>& args) {
  const CommandResult r = runVesalius(args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
}

// `count` markers spread over the CT label `label`'s boundary (inside the scan), seeded.
inline void sampleBoundary(const std::string& label, int count, int seed, const std::string& out) {
  runOk({"markers", "sample", "--labels", kCtLabels, "--table", kCtLabelTable, "--label", label, "--count",
         std::to_string(count), "--seed", std::to_string(seed), "--out", out, "--progress", "none", "--force"});
}

inline MatrixX3d markerPositions(const std::string& markerFile) {
  const MarkerSet set = io::readMarkers(markerFile);
  MatrixX3d P(Eigen::Index(set.markers.size()), 3);
  for (std::size_t k = 0; k < set.markers.size(); ++k) P.row(Eigen::Index(k)) = set.markers[k].position.transpose();
  return P;
}

// Mean distance (mm) from the points P (#P by 3) to `surface`.
inline double meanDistanceToSurface(const MatrixX3d& P, const TriMesh& surface) {
  const TriangleTree tree(surface.V, surface.F);
  double sum = 0;
  for (const ClosestPoint& c : tree.closest(P)) sum += std::sqrt(c.squaredDistance);
  return sum / double(P.rows());
}

// The same to the surface in `surfaceFile`.
inline double meanDistanceToSurface(const MatrixX3d& P, const std::string& surfaceFile) {
  return meanDistanceToSurface(P, io::readTriMesh(surfaceFile));
}

// The CT label's voxel volume, mm^3.
inline double ctLabelVolumeMm3(const std::string& name) {
  const LabelMap map = io::readLabelMap(kCtLabels, kCtLabelTable);
  const Label id = map.table.find(name)->id;
  const Eigen::Vector3d h = map.labels.geometry.spacing;
  return double(std::count(map.labels.values.begin(), map.labels.values.end(), id)) * h.prod();
}

// The CT's largest voxel edge, mm.
inline double ctVoxelMm() { return io::readLabelMap(kCtLabels, kCtLabelTable).labels.geometry.spacing.maxCoeff(); }

}  // namespace vesalius::test
