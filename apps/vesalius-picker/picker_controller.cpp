#include "picker_controller.h"

#include "edge_snap.h"

#include "vesalius/core/error.h"

#include <vtkRenderWindowInteractor.h>

#include <cstdio>
#include <iostream>

namespace vesalius::picker {
namespace {

constexpr double kGrabRadiusPixels = 8;
constexpr double kZoomPerStep = 1.15;
constexpr double kSnapRadius = 3;  // mm

MarkerKind nextKind(MarkerKind kind) {
  switch (kind) {
    case MarkerKind::Landmark: return MarkerKind::IcpMarker;
    case MarkerKind::IcpMarker: return MarkerKind::Attachment;
    case MarkerKind::Attachment: return MarkerKind::Landmark;
  }
  return MarkerKind::Landmark;
}

}  // namespace

PickerController::PickerController(PickerDocument& document, PickerWindow& window, const ScanVolume& scan,
                                   std::string outputPath, bool replaceOutput, double acceptConfidence)
    : document_(document), window_(window), scan_(scan), outputPath_(std::move(outputPath)),
      replaceOutput_(replaceOutput), acceptConfidence_(acceptConfidence), windowLevel_(kCtSoftTissue) {
  if (scan.image().fileType != PixelType::Int16 && scan.image().fileType != PixelType::Int32)
    windowLevel_ = percentileWindowLevel(scan.image());  // not stored as HU: most likely MRI
  window_.setWindowLevel(windowLevel_);
}

void PickerController::leftButtonDown(const MouseEvent& event) {
  lastMouse_ = event;
  if (window_.view3d().contains(event.x, event.y)) {
    drag_ = Drag::Rotate;
    return;
  }
  SliceView* view = window_.sliceViewAt(event.x, event.y);
  if (!view) return;
  if (event.shift) {
    drag_ = Drag::Crosshair;
    dragView_ = view;
    setCrosshair(view->displayToWorld(event.x, event.y));
  } else {
    placeOrGrab(*view, event);
  }
  refresh();
}

void PickerController::placeOrGrab(SliceView& view, const MouseEvent& event) {
  if (const auto grabbed = markerUnder(view, event)) {
    drag_ = Drag::Marker;
    dragView_ = &view;
    draggedMarker_ = *grabbed;
    dragStartPosition_ = document_.marker(*grabbed).position;
    return;
  }
  const Eigen::Vector3d world = pickedPoint(view, event);
  const auto named = kind_ == MarkerKind::Landmark ? document_.nextUndefinedLandmark(namedLandmarkCursor_)
                                                   : std::nullopt;
  if (named) {
    document_.placeNamedMarker(*named, world);
    namedLandmarkCursor_ = *named + 1;
  } else {
    document_.addMarker(kind_, world);
  }
}

void PickerController::leftButtonUp(const MouseEvent& event) {
  if (drag_ == Drag::Marker) {
    document_.dragMarker(draggedMarker_, pickedPoint(*dragView_, event));
    if (document_.marker(draggedMarker_).position != dragStartPosition_)
      document_.finishDrag(draggedMarker_, dragStartPosition_);
  }
  drag_ = Drag::None;
  dragView_ = nullptr;
  refresh();
}

void PickerController::rightButtonDown(const MouseEvent& event) {
  if (!window_.sliceViewAt(event.x, event.y)) return;
  drag_ = Drag::WindowLevel;
  dragStartMouse_ = event;
  dragStartWindowLevel_ = windowLevel_;
}

void PickerController::middleButtonDown(const MouseEvent& event) {
  dragView_ = window_.sliceViewAt(event.x, event.y);
  if (dragView_) drag_ = Drag::Pan;
  lastMouse_ = event;
}

void PickerController::buttonUp() {
  drag_ = Drag::None;
  dragView_ = nullptr;
}

void PickerController::mouseMove(const MouseEvent& event) {
  switch (drag_) {
    case Drag::Marker:
      document_.dragMarker(draggedMarker_, dragView_->displayToWorld(event.x, event.y));
      break;
    case Drag::Crosshair: setCrosshair(dragView_->displayToWorld(event.x, event.y)); break;
    case Drag::WindowLevel:
      windowLevel_ = dragWindowLevel(dragStartWindowLevel_, event.x - dragStartMouse_.x,
                                     event.y - dragStartMouse_.y);
      window_.setWindowLevel(windowLevel_);
      break;
    case Drag::Pan: dragView_->pan(event.x - lastMouse_.x, event.y - lastMouse_.y); break;
    case Drag::Rotate: window_.view3d().rotate(event.x - lastMouse_.x, event.y - lastMouse_.y); break;
    case Drag::None: break;
  }
  lastMouse_ = event;
  updateCursorReadout(event);
  refresh();
}

void PickerController::wheel(const MouseEvent& event, int steps) {
  lastMouse_ = event;
  if (window_.view3d().contains(event.x, event.y)) {
    window_.view3d().zoom(steps > 0 ? kZoomPerStep : 1 / kZoomPerStep);
  } else if (SliceView* view = window_.sliceViewAt(event.x, event.y)) {
    if (event.control)
      view->zoom(steps > 0 ? kZoomPerStep : 1 / kZoomPerStep);
    else
      view->stepSlices(steps);
  }
  updateCursorReadout(event);
  refresh();
}

void PickerController::keyPress(const std::string& keySym, const MouseEvent& event) {
  lastMouse_ = event;
  message_.clear();
  if (event.control) {
    if (keySym == "z" && !document_.undo()) message_ = "nothing to undo";
    if (keySym == "y" && !document_.redo()) message_ = "nothing to redo";
    if (keySym == "s") save();
    if (keySym == "q") quit();
  } else if (keySym == "g") {
    snapToEdges_ = !snapToEdges_;
  } else if (keySym == "k") {
    kind_ = nextKind(kind_);
  } else if (keySym == "1" || keySym == "2" || keySym == "3") {
    kind_ = MarkerKind(keySym[0] - '1');
  } else if (keySym == "Delete" || keySym == "BackSpace" || keySym == "d") {
    deleteMarkerUnder(event);
  } else if (keySym == "a" || keySym == "x") {
    acceptOrRejectPreviewUnder(event, keySym == "a");
  } else if (keySym == "A") {
    acceptAllPreviews();
  } else if (keySym == "n") {
    skipNamedLandmark();
  } else if (keySym == "Prior" || keySym == "Up") {
    stepSlicesUnder(event, 1);
  } else if (keySym == "Next" || keySym == "Down") {
    stepSlicesUnder(event, -1);
  } else if (keySym == "b" || keySym == "t" || keySym == "m") {
    windowLevel_ = keySym == "b" ? kCtBone : keySym == "t" ? kCtSoftTissue : percentileWindowLevel(scan_.image());
    window_.setWindowLevel(windowLevel_);
  } else if (keySym == "r") {
    window_.fitViews();
  }
  refresh();
}

void PickerController::setCrosshair(const Eigen::Vector3d& world) {
  for (SliceView* view : window_.sliceViews()) view->showSliceThrough(world);
}

Eigen::Vector3d PickerController::pickedPoint(const SliceView& view, const MouseEvent& event) const {
  const Eigen::Vector3d world = view.displayToWorld(event.x, event.y);
  return snapToEdges_ ? snapToEdge(scan_.image(), world, view.frame().normal, kSnapRadius) : world;
}

std::optional<std::size_t> PickerController::markerUnder(SliceView& view, const MouseEvent& event,
                                                         bool previewsOnly) const {
  const Eigen::Vector3d world = view.displayToWorld(event.x, event.y);
  return document_.nearestMarker(world, kGrabRadiusPixels * view.millimetresPerPixel(), [&](const Marker& m) {
    return view.isOnSlice(m.position) && (!previewsOnly || m.status == MarkerStatus::Preview);
  });
}

void PickerController::deleteMarkerUnder(const MouseEvent& event) {
  SliceView* view = window_.sliceViewAt(event.x, event.y);
  const auto index = view ? markerUnder(*view, event) : std::nullopt;
  if (!index) {
    message_ = "no marker under the mouse to delete";
    return;
  }
  document_.removeMarker(*index);
}

void PickerController::acceptOrRejectPreviewUnder(const MouseEvent& event, bool accept) {
  SliceView* view = window_.sliceViewAt(event.x, event.y);
  const auto index = view ? markerUnder(*view, event, true) : std::nullopt;
  if (!index) {
    message_ = "no suggestion under the mouse";
    return;
  }
  message_ = (accept ? "accepted " : "rejected ") + document_.marker(*index).label;
  if (accept)
    document_.acceptPreview(*index);
  else
    document_.rejectPreview(*index);
}

void PickerController::acceptAllPreviews() {
  const std::size_t accepted = document_.acceptPreviews(acceptConfidence_);
  char text[120];
  if (acceptConfidence_ > 0)
    std::snprintf(text, sizeof text, "accepted %zu suggestions of confidence >= %.2f", accepted, acceptConfidence_);
  else
    std::snprintf(text, sizeof text, "accepted %zu suggestions", accepted);
  message_ = text;
}

void PickerController::skipNamedLandmark() {
  const auto named = document_.nextUndefinedLandmark(namedLandmarkCursor_);
  if (!named) {
    message_ = "no named landmark left to place";
    return;
  }
  message_ = "skipped " + document_.marker(*named).label + " (missing)";
  if (document_.marker(*named).status != MarkerStatus::Missing) document_.markMissing(*named);
  namedLandmarkCursor_ = *named + 1;
}

void PickerController::stepSlicesUnder(const MouseEvent& event, int steps) {
  if (SliceView* view = window_.sliceViewAt(event.x, event.y)) view->stepSlices(steps);
}

void PickerController::save() {
  try {
    document_.save(outputPath_, replaceOutput_);
    replaceOutput_ = true;  // from now on the file is this session's own
    message_ = "saved " + outputPath_;
  } catch (const Error& e) {
    message_ = std::string("not saved: ") + e.what();
  }
  std::cerr << message_ << "\n";
}

void PickerController::quit() {
  window_.interactor()->SetDone(true);  // TerminateApp() inside Start() crashes VTK 9.1 (docs/design.md)
}

void PickerController::updateCursorReadout(const MouseEvent& event) {
  SliceView* view = window_.sliceViewAt(event.x, event.y);
  if (!view) return;
  const Eigen::Vector3d world = view->displayToWorld(event.x, event.y);
  char text[200];
  if (const auto voxel = scan_.voxelAt(world)) {
    std::snprintf(text, sizeof text, "voxel %d %d %d   LPS %.2f %.2f %.2f mm   value %g", voxel->x(),
                  voxel->y(), voxel->z(), world.x(), world.y(), world.z(), double(scan_.valueAt(*voxel)));
  } else {
    std::snprintf(text, sizeof text, "outside the scan   LPS %.2f %.2f %.2f mm", world.x(), world.y(),
                  world.z());
  }
  cursorLine_ = text;
}

std::string PickerController::stateLine() const {
  std::string line = std::string("placing ") + markerKindName(kind_) + " (k switches)";
  if (snapToEdges_) line += "  snap to edges (g)";
  if (kind_ == MarkerKind::Landmark)
    if (const auto named = document_.nextUndefinedLandmark(namedLandmarkCursor_))
      line += "  next: " + document_.marker(*named).label + " (n skips)";
  if (const std::size_t previews = document_.previewCount())
    line += "  suggestions: " + std::to_string(previews) + " (a, x, A)";
  line += document_.hasUnsavedEdits() ? "   unsaved" : "   saved";
  if (!message_.empty()) line += "   " + message_;
  return line;
}

void PickerController::refresh() {
  window_.setStatus(cursorLine_, stateLine());
  window_.render(document_.markers(), document_.revision());
}

}  // namespace vesalius::picker
