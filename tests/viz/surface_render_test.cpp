// The 3-D surface render. Needs an X display: ctest -L gui under
// xvfb-run -a -s "-screen 0 1280x1024x24 -noreset"; without one the render must refuse cleanly.
#include "vesalius/viz/surface_render.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/label_surface.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace vesalius::viz {
namespace {

// A ball of 10 mm radius at the origin.
TriMesh ball() {
  GridGeometry g;
  g.size = Eigen::Vector3i(30, 30, 30);
  g.origin = Eigen::Vector3d::Constant(-14.5);
  LabelMap map;
  map.labels = Grid<Label>(g, 0);
  for (int k = 0; k < 30; ++k)
    for (int j = 0; j < 30; ++j)
      for (int i = 0; i < 30; ++i)
        map.labels.at(i, j, k) = g.indexToWorld(Eigen::Vector3d(i, j, k)).norm() <= 10;
  return meshing::labelSurface(map, 1);
}

TEST(SurfaceRender, RefusesWithoutADisplay) {
  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  unsetenv("DISPLAY");
  const TriMesh mesh = ball();
  EXPECT_FALSE(canRenderSurfaces());
  EXPECT_THROW(renderSurfaces({{&mesh}}), UsageError);
  if (!saved.empty()) setenv("DISPLAY", saved.c_str(), 1);
}

// VTK aborts the process when it cannot connect to the display it is told of; the render opens the
// connection itself and refuses with one line instead.
TEST(SurfaceRender, RefusesADisplayItCannotOpen) {
  const char* display = std::getenv("DISPLAY");
  const std::string saved = display ? display : "";
  setenv("DISPLAY", ":987", 1);  // no server listens there
  const TriMesh mesh = ball();
  try {
    renderSurfaces({{&mesh}});
    ADD_FAILURE() << "rendered without a display";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot open the X display ':987'"), std::string::npos) << e.what();
  }
  if (saved.empty())
    unsetenv("DISPLAY");
  else
    setenv("DISPLAY", saved.c_str(), 1);
}

TEST(SurfaceRender, BallFillsTheMiddleInItsColour) {
  if (!canRenderSurfaces()) GTEST_SKIP() << "no X display; run under xvfb-run";
  const TriMesh mesh = ball();
  SurfaceRenderOptions options;
  options.width = options.height = 200;
  const RgbImage picture = renderSurfaces({{&mesh, {{220, 40, 40}}, 1.0}}, options);
  ASSERT_EQ(picture.width, 200);
  const Rgb centre = picture.get(100, 100), corner = picture.get(2, 2);
  EXPECT_GT(centre[0], 2 * centre[1]);  // red, shaded
  EXPECT_EQ(corner, options.background);
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/ball.png";
  std::filesystem::create_directories(VESALIUS_TEST_OUTPUT);
  options.write.force = true;
  writeSurfacesPng({{&mesh, {{220, 40, 40}}, 1.0}}, path, options);
  EXPECT_TRUE(std::filesystem::exists(path));
}

TEST(SurfaceRender, RejectsEmptyLayers) {
  if (!canRenderSurfaces()) GTEST_SKIP() << "no X display";
  const TriMesh empty;
  EXPECT_THROW(renderSurfaces({{&empty}}), UsageError);
}

}  // namespace
}  // namespace vesalius::viz
