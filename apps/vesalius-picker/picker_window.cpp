#include "picker_window.h"

#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

namespace vesalius::picker {
namespace {

// xmin, ymin, xmax, ymax of each view; VTK's y runs up from the bottom of the window.
constexpr std::array<double, 4> kAxialViewport{0.0, 0.5, 0.5, 1.0};
constexpr std::array<double, 4> kView3dViewport{0.5, 0.5, 1.0, 1.0};
constexpr std::array<double, 4> kCoronalViewport{0.0, 0.0, 0.5, 0.5};
constexpr std::array<double, 4> kSagittalViewport{0.5, 0.0, 1.0, 0.5};

}  // namespace

PickerWindow::PickerWindow(const ScanVolume& scan, int width, int height) {
  window_ = vtkSmartPointer<vtkRenderWindow>::New();
  window_->SetSize(width, height);
  window_->SetWindowName("Vesalius picker");
  window_->SetMultiSamples(0);  // crisp marker colours, and software GL (Xvfb) stays fast
  interactor_ = vtkSmartPointer<vtkRenderWindowInteractor>::New();
  interactor_->SetRenderWindow(window_);

  slices_[0] = std::make_unique<SliceView>(SliceAxis::Axial, scan, window_, kAxialViewport);
  slices_[1] = std::make_unique<SliceView>(SliceAxis::Coronal, scan, window_, kCoronalViewport);
  slices_[2] = std::make_unique<SliceView>(SliceAxis::Sagittal, scan, window_, kSagittalViewport);
  view3d_ = std::make_unique<View3D>(
      std::array<const SliceView*, 3>{slices_[0].get(), slices_[1].get(), slices_[2].get()}, window_,
      kView3dViewport);
  labelOffset3d_ = 0.01 * (scan.geometry().size.cast<double>().cwiseProduct(scan.geometry().spacing)).norm();

  status_ = vtkSmartPointer<vtkTextActor>::New();
  status_->GetTextProperty()->SetFontSize(13);
  status_->GetTextProperty()->SetColor(0.9, 0.9, 0.9);
  status_->SetPosition(6, 6);
  view3d_->renderer()->AddActor2D(status_);
}

PickerWindow::~PickerWindow() = default;

std::array<SliceView*, 3> PickerWindow::sliceViews() {
  return {slices_[0].get(), slices_[1].get(), slices_[2].get()};
}

SliceView* PickerWindow::sliceViewAt(int displayX, int displayY) {
  for (auto& slice : slices_)
    if (slice->contains(displayX, displayY)) return slice.get();
  return nullptr;
}

void PickerWindow::setWindowLevel(const WindowLevel& windowLevel) {
  for (auto& slice : slices_) slice->setWindowLevel(windowLevel);
}

void PickerWindow::fitViews() {
  for (auto& slice : slices_) slice->fitToScan();
  view3d_->fitToScene();
}

void PickerWindow::setStatus(const std::string& cursorLine, const std::string& stateLine) {
  const std::string text = cursorLine + "\n" + stateLine;
  if (status_->GetInput() && text == status_->GetInput()) return;
  status_->SetInput(text.c_str());
  statusChanged_ = true;
}

void PickerWindow::render(const MarkerSet& markers, std::uint64_t markersRevision) {
  for (auto& slice : slices_) slice->showMarkers(markers, markersRevision);
  if (markersRevision != drawnRevision3d_) {
    view3d_->showMarkers(markers, labelOffset3d_);
    drawnRevision3d_ = markersRevision;
  }
  bool anySliceChanged = false;
  for (auto& slice : slices_) {
    const bool changed = slice->takeChanged();
    slice->renderer()->SetDraw(changed);
    anySliceChanged = anySliceChanged || changed;
  }
  const bool view3dChanged = view3d_->takeChanged();
  view3d_->renderer()->SetDraw(view3dChanged || anySliceChanged || statusChanged_);
  statusChanged_ = false;
  window_->Render();
  for (auto& slice : slices_) slice->renderer()->SetDraw(true);
  view3d_->renderer()->SetDraw(true);
}

}  // namespace vesalius::picker
