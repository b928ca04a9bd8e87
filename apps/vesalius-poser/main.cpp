// vesalius-poser: plays a motion on an anatomy rigged by `vesalius rig`, the skin translucent over the
// tissues, skinned live by LBS, DQS or CoR (issue 6; Sujar et al. 2018, §3.5, §4; docs/cli.md "vesalius-poser").
#include "poser_app.h"

#include "vesalius/core/error.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  vesalius::poser::PoserOptions o;
  CLI::App app{"Play a motion on a rigged anatomy: the skin translucent over bones, muscles and organs.",
               "vesalius-poser"};
  app.add_option("--anatomy", o.anatomyDir, "Anatomy directory written by `vesalius rig`")->required();
  app.add_option("--motion", o.motionPath, "BVH motion (CMU or MakeHuman names; see --map)")->required();
  app.add_option("--map", o.mapPath, "Joint map file: 'motion-joint rig-joint' per line (default as `vesalius pose`)");
  app.add_flag("--motion-lps", o.motionLps, "The motion is in mm LPS (a skeleton.bvh of vesalius), not +Y up");
  app.add_option("--method", o.method, "Skinning at start: lbs, dqs or cor (keys l, d, c switch)")
      ->capture_default_str();
  app.add_option("--fps", o.fps, "Playback rate, frames per second")->capture_default_str();
  app.add_option("--frame", o.frame, "Frame shown at start (0-based)")->capture_default_str();
  app.add_flag("--untangle", o.untangle,
               "Repair the tets each pose inverts, as `vesalius pose` does by default (0.3-1 s a frame, so off for playback)");
  app.add_flag("--restore-volume", o.restoreVolume,
               "Give each pose the volume skinning loses back, as `vesalius pose` does by default (0.1-0.25 s a frame, "
               "so off for playback)");
  app.add_option("--skin-opacity", o.skinOpacity, "Opacity of the skin, 0 to 1")->capture_default_str();
  app.add_option("--save-dir", o.saveDir, "Key s writes the shown meshes to DIR/frame_NNNNN_METHOD/");
  app.add_option("--play", o.playEventsPath, "Play a VTK event-recorder file after start");
  app.add_flag("--exit-after-play", o.exitAfterPlay, "Quit once --play is done");
  app.add_option("--record", o.recordEventsPath, "Record this session's events to a file");
  app.add_option("--screenshot", o.screenshotPath, "Write the window as PNG (after --play) before the event loop");
  app.add_option("--window-width", o.windowWidth, "Window width, pixels")->check(CLI::Range(200, 8000));
  app.add_option("--window-height", o.windowHeight, "Window height, pixels")->check(CLI::Range(200, 8000));
  app.footer(
      "Keys: space play/pause, Left/Right step a frame, l/d/c skin by LBS/DQS/CoR, r front view, s save the "
      "shown pose (--save-dir), q quit; drag to turn, wheel to zoom; the slider at the bottom picks a frame.\n"
      "Example:  vesalius rig --skin body.obj --skeleton testdata/body/default.mhskel --tissue muscles.obj "
      "--out body-rig\n"
      "          vesalius-poser --anatomy body-rig --motion testdata/motion/01_01.bvh --method cor\n"
      "Exit codes: 0 ok, 2 usage (or no display), 3 bad input.");
  try {
    app.parse(argc, argv);
    return vesalius::poser::runPoser(o);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? vesalius::kExitOk : vesalius::kExitUsage;
  } catch (const vesalius::Error& e) {
    std::cerr << "vesalius-poser: " << e.what() << '\n';
    return e.exitCode();
  } catch (const std::exception& e) {
    std::cerr << "vesalius-poser: unexpected error: " << e.what() << '\n';
    return 1;
  }
}
