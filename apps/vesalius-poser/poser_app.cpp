#include "poser_app.h"

#include "anatomy_actors.h"
#include "poser_controller.h"
#include "poser_interactor_style.h"
#include "poser_window.h"

#include "vtk_window_support.h"

#include "vesalius/core/error.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/rigging/rig_session.h"
#include "vesalius/viz/display_connection.h"

#include <filesystem>
#include <iostream>

namespace vesalius::poser {
namespace {

namespace fs = std::filesystem;

void checkOptions(const PoserOptions& o) {
  if (o.method != "lbs" && o.method != "dqs" && o.method != "cor")
    throw UsageError("--method must be lbs, dqs or cor");
  if (!(o.fps > 0 && o.fps <= 1000)) throw UsageError("--fps must be in (0, 1000]");
  if (!(o.skinOpacity >= 0 && o.skinOpacity <= 1)) throw UsageError("--skin-opacity must be in [0, 1]");
  if (!fs::is_directory(o.anatomyDir))
    throw BadInput(o.anatomyDir, "no such anatomy directory (write one with `vesalius rig`)");
}

std::vector<std::string> meshStems(const AnatomyRig& rig) {
  std::vector<std::string> stems;
  for (const std::string& path : rig.meshes) stems.push_back(fs::path(path).stem().string());
  return stems;
}

}  // namespace

int runPoser(const PoserOptions& options) {
  checkOptions(options);
  const posing::RigPoser session = rigging::readRigPoser(options.anatomyDir, options.untangle, options.restoreVolume);
  const rigging::RetargetedMotion motion(io::readBvh(options.motionPath, std::cerr), options.mapPath, options.motionLps, session.rig().skeleton);
  if (options.frame < 0 || options.frame >= motion.frameCount())
    throw UsageError("--frame " + std::to_string(options.frame) + " outside 0.." +
                     std::to_string(motion.frameCount() - 1) + " of " + options.motionPath);
  if (options.method == "cor") session.rig().centres();  // a rig without centres: its BadInput now, not later

  const viz::DisplayConnection connection("vesalius-poser");  // outlives the window, which does not close it
  PoserWindow window(options.windowWidth, options.windowHeight, motion.frameCount());
  window.renderWindow()->SetDisplayId(connection.display);
  AnatomyActorsOptions look;
  look.skinOpacity = options.skinOpacity;
  AnatomyActors actors(session.meshes(), meshStems(session.rig()), window.renderer(), look);
  PoserController controller(session, motion, actors, window, options);
  auto style = vtkSmartPointer<PoserInteractorStyle>::New();
  style->setController(&controller);
  window.interactor()->SetInteractorStyle(style);
  gui::endLoopOnWindowClose(window.interactor());
  window.interactor()->Initialize();
  window.enableSlider([&controller](int frame) { controller.showFrame(frame); });
  controller.showFrame(options.frame);
  controller.resetCamera();

  gui::runEventLoop(window.renderWindow(), window.interactor(),
                    {options.recordEventsPath, options.playEventsPath, options.screenshotPath, options.exitAfterPlay});
  return kExitOk;
}

}  // namespace vesalius::poser
