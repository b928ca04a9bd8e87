// The picker's window: axial (top left), 3D (top right), coronal (bottom left) and sagittal (bottom
// right) views in one vtkRenderWindow, and a two-line status readout in a strip of its own under the 3D
// view (so that a new readout does not render the 3D view again).
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

class vtkRenderer;
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
  // pixels in VTK's offscreen frame buffer. The 3D view shows the slices, so it follows any change:
  // at once, or, with deferView3d, once the slices stop moving.
  void render(const MarkerSet& markers, std::uint64_t markersRevision);
  // While slices scroll, render the 3D view only once `milliseconds` pass without a slice moving (its
  // slice planes lag behind; a change of its own camera, markers or surfaces still renders it at once),
  // by a one-shot timer of the interactor, which must be initialised. 0 (the default): with every step.
  void deferView3d(int milliseconds) { view3dDelayMs_ = milliseconds; }
  bool view3dPending() const { return view3dPending_; }
  void renderView3d();  // the deferred render now
  void timerFired(int timerId);  // the interactor's TimerEvent: renders the 3D view if its timer is due

 private:
  void draw(const std::array<bool, 3>& slices, bool view3d);  // the views flagged, and the readout if new

  vtkSmartPointer<vtkRenderWindow> window_;
  vtkSmartPointer<vtkRenderWindowInteractor> interactor_;
  std::array<std::unique_ptr<SliceView>, 3> slices_;
  std::unique_ptr<View3D> view3d_;
  vtkSmartPointer<vtkRenderer> statusRenderer_;
  vtkSmartPointer<vtkTextActor> status_;
  double labelOffset3d_ = 1;  // mm, from the scan's size
  std::uint64_t drawnRevision3d_ = ~std::uint64_t(0);
  bool statusChanged_ = true;
  int view3dDelayMs_ = 0;
  bool view3dPending_ = false;
  int timerId_ = 0;  // the pending one-shot timer, 0 for none
};

}  // namespace vesalius::picker
