// The picker's command line.
#pragma once

#include <string>
#include <vector>

namespace vesalius::picker {

struct PickerOptions {
  std::string scanPath;           // scan file or DICOM folder
  std::string markersPath;        // markers to start from (never overwritten)
  std::string outputPath;         // where Ctrl+S saves (.mrk.json)
  bool force = false;             // replace an existing output
  std::string restore = "ask";    // restore a newer autosave: yes | no | ask
  std::string landmarkNamesPath;  // one landmark name per line, placed in order
  std::vector<std::string> overlayPaths;  // meshes drawn as contours and 3D surfaces
  std::string labelsPath;         // label map drawn as a translucent colour layer
  double acceptConfidence = 0;    // Shift+A accepts the suggestions of at least this confidence
  std::string playEventsPath;     // vtkInteractorEventRecorder file played after start
  bool exitAfterPlay = false;
  std::string recordEventsPath;   // records this session's events (for new GUI tests)
  std::string screenshotPath;     // PNG of the window, written after playing
  int windowWidth = 1200, windowHeight = 900;
};

// The output path when none is given: "<markers stem>-picked.mrk.json" beside the markers, else
// "<scan stem>-markers.mrk.json" in the current folder. Never the markers input itself.
std::string defaultOutputPath(const PickerOptions& options);

}  // namespace vesalius::picker
