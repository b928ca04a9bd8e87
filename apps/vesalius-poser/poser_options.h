// The poser's command line (docs/cli.md, "vesalius-poser").
#pragma once

#include <string>

namespace vesalius::poser {

struct PoserOptions {
  std::string anatomyDir;       // written by `vesalius rig`
  std::string motionPath;       // BVH (CMU or MakeHuman names)
  std::string mapPath;          // joint map 'motion-joint rig-joint' per line; empty: as `vesalius pose`
  bool motionLps = false;       // the motion is in mm LPS (a skeleton.bvh of vesalius), not +Y up
  std::string method = "lbs";   // lbs | dqs | cor
  double fps = 30;              // playback rate
  int frame = 0;                // frame shown at start
  std::string saveDir;          // key s writes the shown pose here
  double skinOpacity = 0.3;
  bool untangle = false;         // repair inverted tets per frame (posing/untangle_tets.h): 0.3-1 s a frame
  bool restoreVolume = false;    // give the skinned tets their volume back (posing/volume_restoration.h): 0.1-0.25 s a frame
  std::string playEventsPath;   // vtkInteractorEventRecorder file played after start
  bool exitAfterPlay = false;
  std::string recordEventsPath; // records this session's events (for new GUI tests)
  std::string screenshotPath;   // PNG of the window, written after playing
  int windowWidth = 1000, windowHeight = 800;
};

}  // namespace vesalius::poser
