// `vesalius fit` of OpenSim's left hip bone to the test CT's hip_left label, un-attached (issue 4,
// validation 5; Wang et al. 2021, §3.6, fits free organs the same way). The template
// (testdata/skeleton-opensim/Geometry/l_pelvis.vtp) is not a closed 2-manifold, so fit closes it by its
// winding number first (meshing/closed_surface.h) and says so; it is in OpenSim's body frame and in
// metres, which the placement (a similarity from principal axes, then ICP) has to undo. 150 ICP markers are
// sampled on the label's boundary inside the scan (the scan cuts the bone; the cut is not sampled).
// Measured: the marker error, the label's whole boundary against the fitted surface, the volume against
// the label's, and the mesh (no inverted tet). docs/methods/plastic-fit.md has the longer runs.
#include "fit_ct_support.h"

#include <gtest/gtest.h>

namespace vesalius::test {
namespace {

const std::string kTemplate = std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Geometry/l_pelvis.vtp";

std::string path(const std::string& name) { return outputPath("fit_pelvis", name); }

TEST(CliFitPelvis, OpenSimHipBoneFittedToTheHipLabel) {
  const std::string icp = path("hip_icp.mrk.json"), check = path("hip_check.mrk.json"), out = path("hip_fitted.vtu"),
                    surface = path("hip_fitted.vtp"), report = path("hip_fit.json");
  sampleBoundary("hip_left", 150, 1, icp);
  sampleBoundary("hip_left", 1000, 2, check);
  // The closed surface is coarsened as the tet target allows (tet_budget.h), as for any template.
  const CommandResult r =
      runVesalius({"fit", "--template", kTemplate, "--icp", icp, "--unattached", "--target-tets", "5000", "--iterations",
                   "3", "--refits", "1", "--out", out, "--surface-out", surface, "--report", report, "--progress",
                   "none", "--force"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectContains(r.err, "1 boundary edges, 5 non-manifold edges");

  const nlohmann::json m = readJson(report)["metrics"];
  const double before = m["icp_error_mm"]["before"]["mean"], after = m["icp_error_mm"]["after"]["mean"];
  RecordProperty("icp_mean_before_mm", std::to_string(before));
  RecordProperty("icp_mean_after_mm", std::to_string(after));
  RecordProperty("icp_max_after_mm", std::to_string(m["icp_error_mm"]["after"]["max"].get<double>()));
  RecordProperty("placement_scale", std::to_string(m["placement"]["scale"].get<double>()));
  EXPECT_EQ(m["attached"], false);
  EXPECT_EQ(m["markers"]["icp"], 150);
  EXPECT_EQ(m["mesh"]["inverted_after"], 0);
  // The placement finds the bone's orientation: OpenSim's frame (x anterior, y superior, z right) to LPS
  // is x -> -P, y -> S, z -> -L, and the scale turns metres into millimetres.
  const nlohmann::json R = m["placement"]["rotation"];
  EXPECT_LT(R[0][2].get<double>(), -0.95);
  EXPECT_LT(R[1][0].get<double>(), -0.95);
  EXPECT_GT(R[2][1].get<double>(), 0.95);
  EXPECT_NEAR(m["placement"]["scale"].get<double>(), 1000.0, 200.0);  // measured 1124
  // Measured 2.90 -> 0.83 mm after 3 ICP iterations, then 0.24 mm after one refit from that shape (the
  // issue asks 0.5).
  EXPECT_GT(before, 2.0 * after);
  EXPECT_LT(after, 0.5);
  ASSERT_EQ(m["rounds"].size(), 2u);
  EXPECT_GT(m["rounds"][0]["icp_error_mm"]["mean"].get<double>(), 2.0 * after);

  // The label's whole boundary inside the scan, 1,000 points of it, against the fitted surface (after the
  // refit, the boundary of its tets): within one voxel on average.
  const double meanDistance = meanDistanceToSurface(markerPositions(check), surface);
  RecordProperty("boundary_to_fitted_mean_mm", std::to_string(meanDistance));
  EXPECT_LT(meanDistance, ctVoxelMm());
  EXPECT_LT(meanDistance, 2.0);  // measured 1.31 mm on the 3 mm grid

  const double ratio = m["volume_mm3"]["fitted"].get<double>() / ctLabelVolumeMm3("hip_left");
  RecordProperty("volume_over_label", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.2);  // measured 1.17 (the markers lie on the smoothed label surface, outside the voxel centres)
}

}  // namespace
}  // namespace vesalius::test
