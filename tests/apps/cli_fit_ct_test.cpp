// `vesalius fit` on a real scan (Wang et al. 2021, §4.1, issue 4's real-scan validation): the Visible Human gluteus
// medius template (testdata/muscles) fitted to the test CT's gluteus_medius_left label, attached to the
// hip bone where the CT's muscle label touches it (§4.1.2: the insertion; `surface --shared --touching`
// gives the hip's interface with the muscle, and its vertices within 5 mm of the placed template are
// attached), with 150 ICP markers spread over the label's boundary as stand-ins for a radiologist's picks.
// The template is decimated to 500 triangles and the ICP stage capped at 3 iterations so that the test
// stays near a minute; docs/methods/plastic-fit.md has the longer runs. Measured: the marker error, the
// distance from the label's whole boundary to the fitted surface (not only at the markers), the
// attachments, the volume against the label's, and the mesh (no inverted tet).
#include "fit_ct_support.h"

#include <gtest/gtest.h>

namespace vesalius::test {
namespace {

const std::string kTemplate = std::string(VESALIUS_TESTDATA) + "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl";

std::string path(const std::string& name) { return outputPath("fit_ct", name); }

TEST(CliFitCt, GluteusMediusAttachedToTheHipBone) {
  const std::string bone = path("hip_insertion.vtp"), icp = path("gmed_icp.mrk.json"),
                    check = path("gmed_check.mrk.json"), out = path("gmed_fitted.vtu"),
                    surface = path("gmed_fitted.vtp"), report = path("gmed_fit.json");
  runOk({"surface", "--labels", kCtLabels, "--table", kCtLabelTable, "--label", "hip_left", "--shared", "--touching",
         "gluteus_medius_left", "--out", bone, "--progress", "none", "--force"});
  const io::TriMeshSummary insertion = io::summarize(io::readTriMesh(bone));
  RecordProperty("insertion_vertices", std::to_string(insertion.vertices));
  EXPECT_GT(insertion.boundaryEdges, 0);  // a patch of the bone, not its closed surface (9,576 vertices)
  EXPECT_GT(insertion.vertices, 250);     // measured 324
  EXPECT_LT(insertion.vertices, 400);
  EXPECT_EQ(runVesalius({"surface", "--labels", kCtLabels, "--table", kCtLabelTable, "--label", "hip_left",
                         "--touching", "gluteus_medius_left", "--out", path("x.vtp"), "--force"})
                .exitCode,
            2);  // --touching needs --shared
  EXPECT_EQ(runVesalius({"surface", "--labels", kCtLabels, "--table", kCtLabelTable, "--label", "hip_left",
                         "--shared", "--touching", "liver", "--out", path("x.vtp"), "--progress", "none", "--force"})
                .exitCode,
            3);  // they do not touch
  sampleBoundary("gluteus_medius_left", 150, 1, icp);
  sampleBoundary("gluteus_medius_left", 1000, 2, check);
  runOk({"fit", "--template", kTemplate, "--template-faces", "500", "--target-tets", "5000", "--icp", icp,
         "--attach-to", bone, "--attach-radius", "5", "--iterations", "3", "--out", out, "--surface-out", surface,
         "--report", report, "--progress", "none", "--force"});

  const nlohmann::json m = readJson(report)["metrics"];
  const double before = m["icp_error_mm"]["before"]["mean"], after = m["icp_error_mm"]["after"]["mean"];
  RecordProperty("icp_mean_before_mm", std::to_string(before));
  RecordProperty("icp_mean_after_mm", std::to_string(after));
  RecordProperty("icp_max_after_mm", std::to_string(m["icp_error_mm"]["after"]["max"].get<double>()));
  RecordProperty("attachment_mean_mm", std::to_string(m["attachment_error_mm"]["mean"].get<double>()));
  EXPECT_EQ(m["attached"], true);
  EXPECT_EQ(m["markers"]["icp"], 150);
  EXPECT_GT(m["markers"]["attachments"].get<int>(), 250);  // measured 310
  // Measured 2.28 -> 0.25 / 1.01 mm (mean / max); the issue asks 0.5. Attached to every hip vertex within
  // 5 mm instead (1,226), the fit stopped at 0.76 / 6.3 mm (plastic-fit.md).
  EXPECT_LT(after, 0.35);
  EXPECT_LT(m["icp_error_mm"]["after"]["max"].get<double>(), 1.5);
  EXPECT_GT(before, 6.0 * after);
  EXPECT_LT(m["attachment_error_mm"]["mean"].get<double>(), 0.75);  // measured 0.52
  EXPECT_EQ(m["mesh"]["inverted_after"], 0);

  // The label's whole boundary, 1,000 points of it, against the fitted surface: within one voxel on average
  // (measured 0.67 mm on the 3 mm grid; 1.18 with the 5 mm band of attachments).
  const double meanDistance = meanDistanceToSurface(markerPositions(check), surface);
  const double voxel = ctVoxelMm();
  RecordProperty("boundary_to_fitted_mean_mm", std::to_string(meanDistance));
  EXPECT_LT(meanDistance, voxel / 3.0);

  // The fitted volume against the label's voxels (measured 1.04; 1.13 with the 5 mm band, which pulled the
  // muscle onto bone it does not cover).
  const double ratio = m["volume_mm3"]["fitted"].get<double>() / ctLabelVolumeMm3("gluteus_medius_left");
  RecordProperty("volume_over_label", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.1);
}

}  // namespace
}  // namespace vesalius::test
