#include "picker_app.h"

#include "autosave.h"
#include "picker_controller.h"
#include "picker_document.h"
#include "picker_inputs.h"
#include "picker_interactor_style.h"
#include "picker_window.h"
#include "scan_volume.h"
#include "vtk_window_support.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/polydata.h"
#include "vesalius/viz/display_connection.h"

#include <vtkImageMapToColors.h>
#include <vtkLookupTable.h>
#include <vtkRenderWindow.h>

#include <Eigen/LU>

#include <cstdlib>
#include <filesystem>
#include <iostream>

namespace vesalius::picker {
namespace {

const Eigen::Vector3d kOverlayColour(1.0, 0.45, 0.1);
constexpr double kLabelOpacity = 0.35;
// The 3D view follows scrolled slices once they rest this long: scrolling then renders one slice view
// per step. A played session (the GUI tests) renders at every step instead, since timers do not fire
// while events are played and its screenshot must show the 3D view up to date.
constexpr int kView3dDelayMs = 150;

void checkOutputPath(const PickerOptions& options, const std::string& outputPath) {
  namespace fs = std::filesystem;
  if (fileExtension(outputPath) != ".mrk.json")
    throw UsageError("--out must end in .mrk.json (3D Slicer markups): " + outputPath);
  std::error_code error;
  if (!options.markersPath.empty() && fs::exists(outputPath, error) &&
      fs::equivalent(outputPath, options.markersPath, error))
    throw UsageError("--out " + outputPath + " is the --markers input, which is never overwritten");
  if (fs::exists(outputPath, error) && !options.force)
    throw UsageError(outputPath + " exists; pass --force to replace it or choose another --out");
}

vtkSmartPointer<vtkLookupTable> labelColours(const LabelTable& table) {
  Label highest = 0;
  for (const LabelEntry& entry : table.entries) highest = std::max(highest, entry.id);
  auto lookup = vtkSmartPointer<vtkLookupTable>::New();
  lookup->SetNumberOfTableValues(highest + 1);
  lookup->SetTableRange(0, highest);
  for (int id = 0; id <= highest; ++id) lookup->SetTableValue(id, 0, 0, 0, 0);
  for (const LabelEntry& entry : table.entries)
    lookup->SetTableValue(entry.id, entry.color[0] / 255.0, entry.color[1] / 255.0, entry.color[2] / 255.0,
                          kLabelOpacity);
  return lookup;
}

void addLabelLayers(PickerWindow& window, const std::string& labelsPath) {
  const LabelMap labels = io::readLabelMap(labelsPath);
  const auto voxels = indexSpaceLabels(labels.labels);
  const auto worldToIndex = toVtkMatrix(labels.labels.geometry.indexToWorldMatrix().inverse());
  const auto lookup = labelColours(labels.table);
  for (SliceView* view : window.sliceViews()) {
    auto colours = vtkSmartPointer<vtkImageMapToColors>::New();
    colours->SetLookupTable(lookup);
    colours->SetOutputFormatToRGBA();
    view->addLabelLayer(voxels, worldToIndex, colours);
  }
}

void addOverlays(PickerWindow& window, const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    const auto surface = io::toPolyData(readOverlaySurface(path));
    for (SliceView* view : window.sliceViews()) view->addSurfaceContour(surface, kOverlayColour);
    window.view3d().addSurface(surface, kOverlayColour);
  }
}

}  // namespace

std::string defaultOutputPath(const PickerOptions& options) {
  namespace fs = std::filesystem;
  if (!options.markersPath.empty()) {
    const std::string stem =
        options.markersPath.substr(0, options.markersPath.size() - fileExtension(options.markersPath).size());
    return stem + "-picked.mrk.json";
  }
  const fs::path scan = fs::path(options.scanPath).lexically_normal();
  std::string name = (scan.has_filename() ? scan.filename() : scan.parent_path().filename()).string();
  name = name.substr(0, name.size() - fileExtension(name).size());
  return name + "-markers.mrk.json";
}

int runPicker(const PickerOptions& options) {
  const std::string outputPath = options.outputPath.empty() ? defaultOutputPath(options) : options.outputPath;
  checkOutputPath(options, outputPath);
  const ScanVolume scan(io::readScan(options.scanPath));
  const std::string autosavePath = autosavePathFor(outputPath);
  bool restored = false;
  MarkerSet markers = initialMarkers(options, autosavePath, restored);
  if (!options.landmarkNamesPath.empty()) addNamedLandmarks(markers, options.landmarkNamesPath);
  PickerDocument document(std::move(markers), restored);
  document.setAutosavePath(autosavePath);
  if (restored) std::cerr << "restored unsaved markers from " << autosavePath << "\n";

  const viz::DisplayConnection connection("vesalius-picker");  // outlives the window, which does not close it
  PickerWindow window(scan, options.windowWidth, options.windowHeight);
  window.renderWindow()->SetDisplayId(connection.display);
  if (options.playEventsPath.empty()) window.deferView3d(kView3dDelayMs);
  if (!options.labelsPath.empty()) addLabelLayers(window, options.labelsPath);
  addOverlays(window, options.overlayPaths);
  PickerController controller(document, window, scan, outputPath, options.force, options.acceptConfidence);
  auto style = vtkSmartPointer<PickerInteractorStyle>::New();
  style->setController(&controller);
  window.interactor()->SetInteractorStyle(style);
  gui::endLoopOnWindowClose(window.interactor());
  window.interactor()->Initialize();
  window.renderWindow()->Render();  // the viewports have their pixel sizes from here on
  window.fitViews();
  controller.refresh();

  gui::runEventLoop(window.renderWindow(), window.interactor(),
                    {options.recordEventsPath, options.playEventsPath, options.screenshotPath, options.exitAfterPlay});
  document.autosave();
  return kExitOk;
}

}  // namespace vesalius::picker
