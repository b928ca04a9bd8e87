// vesalius-picker: pick landmarks, ICP markers and attachments on a scan's slices (docs/picker.md).
#include "picker_app.h"

#include "vesalius/core/error.h"

#include <CLI/CLI.hpp>

#include <iostream>

int main(int argc, char** argv) {
  vesalius::picker::PickerOptions options;
  CLI::App app{"Pick landmarks, ICP markers and attachments on a scan's slices.", "vesalius-picker"};
  app.add_option("scan", options.scanPath, "Scan file (NIfTI, NRRD, MetaImage, DICOM) or DICOM folder")
      ->required();
  app.add_option("--markers", options.markersPath, "Markers to start from (.mrk.json, .fcsv, .csv); never overwritten");
  app.add_option("--out", options.outputPath, "Where Ctrl+S saves (.mrk.json, LPS); default <markers>-picked.mrk.json");
  app.add_flag("--force", options.force, "Replace an existing --out file");
  app.add_option("--restore", options.restore, "Restore a newer autosave: yes, no or ask")
      ->check(CLI::IsMember({"yes", "no", "ask"}));
  app.add_option("--landmark-names", options.landmarkNamesPath, "Landmark names to place in order, one a line");
  app.add_option("--overlay", options.overlayPaths, "Mesh drawn as a contour on the slices and a surface in 3D");
  app.add_option("--labels", options.labelsPath, "Label map drawn as a translucent colour layer");
  app.add_option("--accept-confidence", options.acceptConfidence,
                 "Shift+A accepts the suggestions (previews) of at least this confidence; 0: all")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--play", options.playEventsPath, "Play a VTK event-recorder file after start");
  app.add_flag("--exit-after-play", options.exitAfterPlay, "Quit (autosaving) once --play is done");
  app.add_option("--record", options.recordEventsPath, "Record this session's events to a file");
  app.add_option("--screenshot", options.screenshotPath, "Write the window as PNG before the event loop");
  app.add_option("--window-width", options.windowWidth, "Window width, pixels")->check(CLI::Range(200, 8000));
  app.add_option("--window-height", options.windowHeight, "Window height, pixels")->check(CLI::Range(200, 8000));
  app.footer("Example:  vesalius-picker ct.nii.gz --markers liver.mrk.json --overlay liver.obj --out liver-picked.mrk.json\n"
             "Exit codes: 0 ok, 2 usage, 3 bad input. Keys and mouse: docs/picker.md.");
  try {
    app.parse(argc, argv);
    return vesalius::picker::runPicker(options);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? vesalius::kExitOk : vesalius::kExitUsage;
  } catch (const vesalius::Error& e) {
    std::cerr << "vesalius-picker: " << e.what() << '\n';
    return e.exitCode();
  } catch (const std::exception& e) {
    std::cerr << "vesalius-picker: unexpected error: " << e.what() << '\n';
    return 1;
  }
}
