#include "picker_window.h"

#include "picker_render_window.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>

namespace vesalius::picker {
namespace {

// xmin, ymin, xmax, ymax of each view; VTK's y runs up from the bottom of the window.
constexpr std::array<double, 4> kAxialViewport{0.0, 0.5, 0.5, 1.0};
constexpr std::array<double, 4> kView3dQuadrant{0.5, 0.5, 1.0, 1.0};  // the 3D view above the status strip
constexpr std::array<double, 4> kCoronalViewport{0.0, 0.0, 0.5, 0.5};
constexpr std::array<double, 4> kSagittalViewport{0.5, 0.0, 1.0, 0.5};

constexpr int kStatusPixels = 40;  // two lines of 13-point text

void onTimer(vtkObject*, unsigned long, void* window, void* timerId) {
  static_cast<PickerWindow*>(window)->timerFired(*static_cast<int*>(timerId));
}

}  // namespace

PickerWindow::PickerWindow(const ScanVolume& scan, int width, int height) {
  window_ = newPickerRenderWindow();
  window_->SetSize(width, height);
  window_->SetWindowName("Vesalius picker");
  window_->SetMultiSamples(0);  // crisp marker colours, and software GL (Xvfb) stays fast
  interactor_ = vtkSmartPointer<vtkRenderWindowInteractor>::New();
  interactor_->SetRenderWindow(window_);

  slices_[0] = std::make_unique<SliceView>(SliceAxis::Axial, scan, window_, kAxialViewport);
  slices_[1] = std::make_unique<SliceView>(SliceAxis::Coronal, scan, window_, kCoronalViewport);
  slices_[2] = std::make_unique<SliceView>(SliceAxis::Sagittal, scan, window_, kSagittalViewport);
  const double statusTop = kView3dQuadrant[1] + double(kStatusPixels) / std::max(height, 2 * kStatusPixels);
  view3d_ = std::make_unique<View3D>(
      std::array<const SliceView*, 3>{slices_[0].get(), slices_[1].get(), slices_[2].get()}, window_,
      std::array<double, 4>{kView3dQuadrant[0], statusTop, kView3dQuadrant[2], kView3dQuadrant[3]});
  labelOffset3d_ = 0.01 * (scan.geometry().size.cast<double>().cwiseProduct(scan.geometry().spacing)).norm();

  status_ = vtkSmartPointer<vtkTextActor>::New();
  status_->GetTextProperty()->SetFontSize(13);
  status_->GetTextProperty()->SetColor(0.9, 0.9, 0.9);
  status_->SetPosition(6, 4);
  statusRenderer_ = vtkSmartPointer<vtkRenderer>::New();
  statusRenderer_->SetViewport(kView3dQuadrant[0], kView3dQuadrant[1], kView3dQuadrant[2], statusTop);
  statusRenderer_->SetBackground(view3d_->renderer()->GetBackground());
  statusRenderer_->InteractiveOff();
  statusRenderer_->AddActor2D(status_);
  window_->AddRenderer(statusRenderer_);

  auto timer = vtkSmartPointer<vtkCallbackCommand>::New();
  timer->SetCallback(onTimer);
  timer->SetClientData(this);
  interactor_->AddObserver(vtkCommand::TimerEvent, timer);
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
  std::array<bool, 3> sliceChanged{};
  for (int i = 0; i < 3; ++i) sliceChanged[std::size_t(i)] = slices_[std::size_t(i)]->takeChanged();
  const bool anySliceChanged = sliceChanged[0] || sliceChanged[1] || sliceChanged[2];
  const bool view3dNow = view3d_->takeChanged() || (anySliceChanged && view3dDelayMs_ <= 0);
  view3dPending_ = (view3dPending_ || anySliceChanged) && !view3dNow;
  draw(sliceChanged, view3dNow);
  // Only a slice that moved restarts the wait (a mouse moving over the views does not).
  if (!view3dPending_ || !anySliceChanged || !interactor_->GetInitialized()) return;
  if (timerId_) interactor_->DestroyTimer(timerId_);
  timerId_ = interactor_->CreateOneShotTimer(unsigned(view3dDelayMs_));
}

void PickerWindow::timerFired(int timerId) {
  if (timerId != timerId_) return;
  timerId_ = 0;
  if (view3dPending_) renderView3d();
}

void PickerWindow::renderView3d() {
  view3dPending_ = false;
  draw({false, false, false}, true);
}

void PickerWindow::draw(const std::array<bool, 3>& slices, bool view3d) {
  for (int i = 0; i < 3; ++i) slices_[std::size_t(i)]->renderer()->SetDraw(slices[std::size_t(i)]);
  view3d_->renderer()->SetDraw(view3d);
  statusRenderer_->SetDraw(statusChanged_);
  statusChanged_ = false;
  window_->Render();
  for (auto& slice : slices_) slice->renderer()->SetDraw(true);
  view3d_->renderer()->SetDraw(true);
  statusRenderer_->SetDraw(true);
}

}  // namespace vesalius::picker
