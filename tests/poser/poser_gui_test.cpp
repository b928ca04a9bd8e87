// Drives vesalius-poser for real (under Xvfb, as scripts/test.sh runs ctest) by playing a
// vtkInteractorEventRecorder file kept beside this test, on MakeHuman's body rigged coarsely by
// `vesalius rig` with one tissue inside it (the skin eroded by up to 1 cm of fat, `vesalius fat erode`: the
// muscle surface of Dicko et al. 2013, §5; 5.4 mm on average, less where the body is thin) and the CMU motion 01_01.
//  - What the poser shows is what `vesalius pose` writes: after stepping to frame 400 the points of the
//    skin and tissue actors (saved by key s) equal `pose --frame 400 --method m --no-restore-volume
//    --no-untangle`'s meshes (the viewer skins without the volume restoration and the tet repair unless
//    --restore-volume, --untangle) to 1e-6 mm for
//    DQS, CoR and LBS, switched live by keys d, c, l in that order; the methods' skins differ.
//  - The screenshot shows the tissue through the translucent skin: inside the body's silhouette most
//    pixels have the tissue's red hue blended with the skin's, hardly any the tissue's own, and with an
//    opaque skin hardly any have either.
//  - A click on the slider shows the frame under the mouse, again as `pose` writes it.
//  - Bad inputs and no display end with one line and the documented exit code.
#include "run_command.h"

#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkPNGReader.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace vesalius {
namespace {

namespace fs = std::filesystem;
using test::runVesalius;  // runs vesalius-poser here

const std::string kData = VESALIUS_TESTDATA;
const std::string kMotion = kData + "/motion/01_01.bvh";
constexpr int kFrame = 400;  // mid-motion: knees bent, arms moving

std::string freshDir(const std::string& name) {
  const fs::path dir = fs::path(test::outputDir()) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// Runs the `vesalius` program; its output goes to `log`, shown on failure.
void runCli(const std::string& args, const std::string& log) {
  const std::string command = std::string("'") + VESALIUS_CLI + "' " + args + " >'" + log + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  ASSERT_EQ(status, 0) << command << "\n" << text.str();
}

// A coarse rig of MakeHuman's neutral body (decimetres, +Y up: `rig` converts it and the tissue to mm
// LPS) with the skin eroded by up to 0.1 dm = 1 cm as its tissue mesh `muscles`. Rigging takes most of a test's
// time (about 20 s), so the tests share one rig, made by whichever comes first (ctest runs them as
// parallel processes: a file lock orders them) and again whenever `vesalius` was built after it.
std::string sharedRig() {
  const fs::path dir = fs::path(test::outputDir()) / "rig", done = dir / "done";
  const int lock = open((test::outputDir() + "/rig.lock").c_str(), O_CREAT | O_RDWR, 0644);
  EXPECT_GE(lock, 0);
  flock(lock, LOCK_EX);
  if (!fs::exists(done) || fs::last_write_time(done) < fs::last_write_time(VESALIUS_CLI)) {
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string skin = kData + "/body/shapes/mh_neutral_body.obj", muscles = (dir / "muscles.obj").string();
    runCli("fat erode --skin '" + skin + "' --thickness 0.1 --out '" + muscles + "'", (dir / "erode.log").string());
    runCli("rig --skin '" + skin + "' --skeleton '" + kData + "/body/default.mhskel' --base-mesh '" + kData +
               "/body/base.obj' --tissue '" + muscles + "' --voxel-size 8 --target-tets 15000 --out '" +
               (dir / "anatomy").string() + "'",
           (dir / "rig.log").string());
    if (!::testing::Test::HasFailure()) std::ofstream(done) << "made by poser_gui_tests\n";
  }
  flock(lock, LOCK_UN);
  close(lock);
  return (dir / "anatomy").string();
}

double maxDistance(const MatrixX3d& a, const MatrixX3d& b) {
  EXPECT_EQ(a.rows(), b.rows());
  if (a.rows() != b.rows()) return 1e9;
  return (a - b).rowwise().norm().maxCoeff();
}

TEST(PoserGui, ShowsThePoseCommandsSkinAndTissueForEachMethod) {
  const std::string dir = freshDir("methods"), rig = sharedRig();
  const auto run = runVesalius({"--anatomy", rig, "--motion", kMotion, "--frame", std::to_string(kFrame - 3),
                                "--save-dir", dir + "/shown", "--play", VESALIUS_POSER_EVENTS "/step_and_switch.events",
                                "--exit-after-play", "--window-width", "600", "--window-height", "600"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::map<std::string, MatrixX3d> shownSkin;
  for (const std::string method : {"lbs", "dqs", "cor"}) {
    const std::string posed = dir + "/pose_" + method;
    runCli("pose --anatomy '" + rig + "' --motion '" + kMotion + "' --frame " + std::to_string(kFrame) +
               " --method " + method + " --no-restore-volume --no-untangle --out '" + posed + "'",
           dir + "/pose_" + method + ".log");
    const std::string shown = dir + "/shown/frame_00400_" + method;
    for (const std::string mesh : {"skin.obj", "muscles.obj"}) {
      const MatrixX3d expected = io::readTriMesh(posed + "/" + mesh).V;
      const MatrixX3d got = io::readTriMesh(shown + "/" + mesh).V;
      EXPECT_LE(maxDistance(got, expected), 1e-6) << method << " " << mesh;
    }
    shownSkin[method] = io::readTriMesh(shown + "/skin.obj").V;
  }
  // The methods differ where joints bend (DQS bulges, LBS shrinks, CoR in between).
  const double lbsDqs = maxDistance(shownSkin["lbs"], shownSkin["dqs"]);
  const double lbsCor = maxDistance(shownSkin["lbs"], shownSkin["cor"]);
  std::cout << "max skin difference at frame " << kFrame << ": LBS-DQS " << lbsDqs << " mm, LBS-CoR " << lbsCor
            << " mm\n";
  EXPECT_GT(lbsDqs, 1.0);
  EXPECT_GT(lbsCor, 1.0);
}

// With --restore-volume --untangle the viewer shows what `vesalius pose` writes by default.
TEST(PoserGui, RestoringTheVolumeShowsThePoseCommandsDefault) {
  const std::string dir = freshDir("restored"), rig = sharedRig();
  const auto run = runVesalius({"--anatomy", rig, "--motion", kMotion, "--frame", std::to_string(kFrame - 3),
                                "--restore-volume", "--untangle", "--save-dir", dir + "/shown", "--play",
                                VESALIUS_POSER_EVENTS "/step_and_switch.events", "--exit-after-play", "--window-width",
                                "600", "--window-height", "600"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const std::string posed = dir + "/pose_cor";
  runCli("pose --anatomy '" + rig + "' --motion '" + kMotion + "' --frame " + std::to_string(kFrame) +
             " --method cor --out '" + posed + "'",
         posed + ".log");
  for (const std::string mesh : {"skin.obj", "muscles.obj"})
    EXPECT_LE(maxDistance(io::readTriMesh(dir + "/shown/frame_00400_cor/" + mesh).V,
                          io::readTriMesh(posed + "/" + mesh).V),
              1e-6)
        << mesh;
}

// A click on the slider jumps to the frame under the mouse: VTK's 2D slider track runs from 0.05 to 0.95
// of the window's width less half an end cap (0.025 of the width) at each end, frames 0 to 2751 along it.
TEST(PoserGui, SliderClicksShowTheFrameUnderTheMouse) {
  const std::string dir = freshDir("slider"), rig = sharedRig();
  const auto run = runVesalius({"--anatomy", rig, "--motion", kMotion, "--save-dir", dir + "/shown", "--play",
                                VESALIUS_POSER_EVENTS "/slider_clicks.events", "--exit-after-play", "--window-width",
                                "600", "--window-height", "600"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  std::vector<int> frames;
  for (const auto& entry : fs::directory_iterator(dir + "/shown"))
    frames.push_back(std::stoi(entry.path().filename().string().substr(6, 5)));  // frame_NNNNN_lbs
  std::sort(frames.begin(), frames.end());
  ASSERT_EQ(frames.size(), 2u);
  const double start = 0.05 * 600 + 0.0125 * 600, end = 0.95 * 600 - 0.0125 * 600, last = 2751;
  EXPECT_NEAR(frames[0], (165 - start) / (end - start) * last, 3);  // a pixel is 5.2 frames
  EXPECT_NEAR(frames[1], (300 - start) / (end - start) * last, 3);
  for (int frame : frames) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d_lbs", frame);
    const std::string posed = dir + "/pose_" + std::to_string(frame);
    runCli("pose --anatomy '" + rig + "' --motion '" + kMotion + "' --frame " + std::to_string(frame) +
               " --method lbs --no-restore-volume --no-untangle --out '" + posed + "'",
           posed + ".log");
    EXPECT_LE(maxDistance(io::readTriMesh(dir + "/shown/" + name + "/skin.obj").V,
                          io::readTriMesh(posed + "/skin.obj").V),
              1e-6)
        << name;
  }
}

// Pixels of a screenshot, within the band between the status line and the slider.
struct PixelCounts {
  long body = 0;         // not background: the skin's silhouette
  long tissueHue = 0;    // red over green as the tissue shows through the skin (1.6 to 2.8)
  long pureTissue = 0;   // red over green as the tissue alone (above 2.8: its colour 0.72, 0.22, 0.20)
};

PixelCounts countPixels(const std::string& png) {
  auto reader = vtkSmartPointer<vtkPNGReader>::New();
  reader->SetFileName(png.c_str());
  reader->Update();
  vtkImageData* image = reader->GetOutput();
  const int width = image->GetDimensions()[0], height = image->GetDimensions()[1];
  PixelCounts counts;
  for (int y = height / 8; y < height * 7 / 8; ++y)
    for (int x = 0; x < width; ++x) {
      const double r = image->GetScalarComponentAsDouble(x, y, 0, 0), g = image->GetScalarComponentAsDouble(x, y, 0, 1),
                   b = image->GetScalarComponentAsDouble(x, y, 0, 2);
      if (std::max({r, g, b}) < 40) continue;  // background 0.09, 0.09, 0.11 (23, 23, 28)
      ++counts.body;
      const double hue = r / std::max(g, 1.0);
      if (hue > 2.8) ++counts.pureTissue;
      else if (hue > 1.6) ++counts.tissueHue;
    }
  return counts;
}

TEST(PoserGui, TissueShowsThroughTheTranslucentSkinOnly) {
  const std::string dir = freshDir("screenshot"), rig = sharedRig();
  PixelCounts counts[2];
  const char* opacities[2] = {"0.3", "1"};
  for (int k = 0; k < 2; ++k) {
    const std::string png = dir + "/opacity_" + opacities[k] + ".png";
    const auto run = runVesalius({"--anatomy", rig, "--motion", kMotion, "--frame", std::to_string(kFrame),
                                  "--method", "cor", "--skin-opacity", opacities[k], "--screenshot", png,
                                  "--play", VESALIUS_POSER_EVENTS "/nothing.events", "--exit-after-play",
                                  "--window-width", "600", "--window-height", "600"});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    counts[k] = countPixels(png);
    std::cout << "skin opacity " << opacities[k] << ": " << counts[k].body << " body pixels, "
              << counts[k].tissueHue << " of the tissue's hue through the skin, " << counts[k].pureTissue
              << " of the tissue alone\n";
  }
  const PixelCounts& translucent = counts[0];
  const PixelCounts& opaque = counts[1];
  EXPECT_GT(translucent.body, 20000);
  EXPECT_GT(translucent.tissueHue, 0.5 * translucent.body);  // the tissue fills most of the body
  EXPECT_LT(translucent.tissueHue, 0.97 * translucent.body);  // a rim of skin alone: the fat
  // Seen through the skin, and hidden by an opaque one, but for a few dozen pixels at the fingertips,
  // where the erosion had no room and the posed tissue meets the skin (measured: 80 and 23 of 39,415).
  EXPECT_LT(translucent.pureTissue, 0.005 * translucent.body);
  EXPECT_LT(opaque.tissueHue + opaque.pureTissue, 0.002 * translucent.body);
  // The same silhouette; the translucent skin's darkest rim falls below the background threshold.
  EXPECT_NEAR(opaque.body, translucent.body, 0.05 * translucent.body);
}

TEST(PoserGui, BadInputsEndWithOneLine) {
  const std::string dir = freshDir("errors");
  auto run = runVesalius({"--anatomy", dir + "/missing", "--motion", kMotion});
  EXPECT_EQ(run.exitCode, 3);
  test::expectContains(run.err, "no such anatomy directory");
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;

  run = runVesalius({"--anatomy", dir, "--motion", kMotion});  // a folder that is no rig
  EXPECT_EQ(run.exitCode, 3) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;

  run = runVesalius({"--anatomy", dir, "--motion", kMotion, "--method", "fem"});
  EXPECT_EQ(run.exitCode, 2);
  test::expectContains(run.err, "--method must be lbs, dqs or cor");

  run = runVesalius({"--help"});
  EXPECT_EQ(run.exitCode, 0);
  test::expectContains(run.out, "Example:");
}

TEST(PoserGui, BadMotionAndNoDisplayEndWithOneLine) {
  const std::string rig = sharedRig();
  auto run = runVesalius({"--anatomy", rig, "--motion", kData + "/bad/bvh_non_numeric.bvh"});
  EXPECT_EQ(run.exitCode, 3);
  test::expectContains(run.err, "bvh_non_numeric.bvh");
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;

  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  unsetenv("DISPLAY");
  run = runVesalius({"--anatomy", rig, "--motion", kMotion});
  if (!saved.empty()) setenv("DISPLAY", saved.c_str(), 1);
  EXPECT_EQ(run.exitCode, 2);
  test::expectContains(run.err, "cannot open the X display");
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
}

}  // namespace
}  // namespace vesalius
