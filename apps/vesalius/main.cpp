// vesalius: patient-specific anatomical models from CT and MRI scans. One subcommand per step.
#include "common.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/core/transparent_huge_pages.h"

#include <iostream>

int main(int argc, char** argv) {
  vesalius::restartWithTransparentHugePages(argv);  // the fits' and rigs' matrices fault in 2 MB at a time
  vesalius::installCleanupOnSignal();  // Ctrl-C during a write leaves no temporary file
  CLI::App app{"Vesalius: patient-specific anatomical models from CT and MRI scans.", "vesalius"};
  app.require_subcommand(1);
  app.set_version_flag("--version", VESALIUS_VERSION);
  app.footer(
      "Exit codes: 0 ok, 2 usage, 3 bad input, 4 numerical failure.\n"
      "Example:  vesalius demo --out demo-output\n"
      "Run 'vesalius COMMAND --help' for the options and an example of each command.");
  vesalius::cli::addInfoCommand(app);
  vesalius::cli::addSegmentCommand(app);
  vesalius::cli::addLabelsCommand(app);
  vesalius::cli::addSurfaceCommand(app);
  vesalius::cli::addTetmeshCommand(app);
  vesalius::cli::addMarkersCommand(app);
  vesalius::cli::addFitCommand(app);
  vesalius::cli::addSeparateCommand(app);
  vesalius::cli::addRigCommand(app);
  vesalius::cli::addPoseCommand(app);
  vesalius::cli::addFatCommand(app);
  vesalius::cli::addReferenceCommand(app);
  vesalius::cli::addTransferCommand(app);
  vesalius::cli::addPatientCommand(app);
  vesalius::cli::addDemoCommand(app);

  vesalius::cli::slicerArguments(argc, argv);  // 3D Slicer passes --skin_thickness for --skin-thickness
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help or --version
    // One line, as every other error: CLI11's own adds "Run with --help for more information." below it.
    std::cerr << "vesalius: " << e.what() << " (see vesalius --help)\n";
    return vesalius::kExitUsage;
  } catch (const vesalius::Error& e) {
    std::cerr << "vesalius: " << vesalius::cli::errorMessage(e) << '\n';
    return e.exitCode();
  } catch (const std::exception& e) {
    std::cerr << "vesalius: unexpected error: " << e.what() << '\n';
    return 1;
  }
  return vesalius::kExitOk;
}
