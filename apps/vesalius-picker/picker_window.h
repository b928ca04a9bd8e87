// The picker's window: axial (top left), 3D (top right), coronal (bottom left) and sagittal (bottom
// right) views in one vtkRenderWindow, and a two-line status readout in the 3D view.
#pragma once

#include "scan_volume.h"
#include "slice_view.h"
#include "view_3d.h"

#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>

class vtkTextActor;

namespace vesalius::picker {

class PickerWindow {
 public:
  PickerWindow(const ScanVolume& scan, int width, int height);
  ~PickerWindow();

  vtkRenderWindow* renderWindow() const { return window_; }
  vtkRenderWindowInteractor* interactor() const { return interactor_; }
  std::array<SliceView*, 3> sliceViews();
  SliceView* sliceViewAt(int displayX, int displayY);  // nullptr outside the slice views
  View3D& view3d() { return *view3d_; }

  void setWindowLevel(const WindowLevel& windowLevel);
  void fitViews();
  void setStatus(const std::string& cursorLine, const std::string& stateLine);
  // Redraws the markers where `markersRevision` or the view changed, and renders the views whose
  // content changed (all of them when VTK renders by itself, e.g. on expose); the others keep their
  // pixels in VTK's offscreen frame buffer. The 3D view shows the slices, so it follows any change.
  void render(const MarkerSet& markers, std::uint64_t markersRevision);
  // Writes what the window shows as PNG.

 private:
  vtkSmartPointer<vtkRenderWindow> window_;
  vtkSmartPointer<vtkRenderWindowInteractor> interactor_;
  std::array<std::unique_ptr<SliceView>, 3> slices_;
  std::unique_ptr<View3D> view3d_;
  vtkSmartPointer<vtkTextActor> status_;
  double labelOffset3d_ = 1;  // mm, from the scan's size
  std::uint64_t drawnRevision3d_ = ~std::uint64_t(0);
  bool statusChanged_ = true;
};

}  // namespace vesalius::picker
