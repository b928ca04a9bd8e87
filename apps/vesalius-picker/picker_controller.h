// What the picker does with mouse and keys: places, drags and deletes markers in the document, accepts
// or rejects suggestions, moves slices, zoom, pan, window/level, undo/redo, save. Every shortcut is
// listed in docs/picker.md.
#pragma once

#include "picker_document.h"
#include "picker_window.h"
#include "scan_volume.h"
#include "window_level.h"

#include <Eigen/Core>

#include <optional>
#include <string>

namespace vesalius::picker {

struct MouseEvent {
  int x = 0, y = 0;  // display pixels, y up from the bottom of the window
  bool shift = false, control = false;
};

class PickerController {
 public:
  // `acceptConfidence`: Shift+A accepts the suggestions of at least this confidence (0: all).
  PickerController(PickerDocument& document, PickerWindow& window, const ScanVolume& scan,
                   std::string outputPath, bool replaceOutput, double acceptConfidence = 0);

  void leftButtonDown(const MouseEvent& event);
  void leftButtonUp(const MouseEvent& event);
  void rightButtonDown(const MouseEvent& event);
  void middleButtonDown(const MouseEvent& event);
  void buttonUp();  // right or middle
  void mouseMove(const MouseEvent& event);
  void wheel(const MouseEvent& event, int steps);  // steps > 0: forward
  void keyPress(const std::string& keySym, const MouseEvent& event);

  void refresh();  // status line, markers, render

 private:
  enum class Drag { None, Marker, Crosshair, WindowLevel, Pan, Rotate };

  void placeOrGrab(SliceView& view, const MouseEvent& event);
  void setCrosshair(const Eigen::Vector3d& world);
  void deleteMarkerUnder(const MouseEvent& event);
  void acceptOrRejectPreviewUnder(const MouseEvent& event, bool accept);
  void acceptAllPreviews();
  void skipNamedLandmark();
  void save();
  void quit();
  void stepSlicesUnder(const MouseEvent& event, int steps);
  void updateCursorReadout(const MouseEvent& event);
  std::optional<std::size_t> markerUnder(SliceView& view, const MouseEvent& event, bool previewsOnly = false) const;
  // The world point under the mouse, moved to the strongest edge nearby when snapping is on.
  Eigen::Vector3d pickedPoint(const SliceView& view, const MouseEvent& event) const;
  std::string stateLine() const;

  PickerDocument& document_;
  PickerWindow& window_;
  const ScanVolume& scan_;
  std::string outputPath_;
  bool replaceOutput_;
  double acceptConfidence_;
  MarkerKind kind_ = MarkerKind::Landmark;
  bool snapToEdges_ = false;
  WindowLevel windowLevel_;
  std::size_t namedLandmarkCursor_ = 0;  // where the search for the next name to place starts

  Drag drag_ = Drag::None;
  SliceView* dragView_ = nullptr;
  std::size_t draggedMarker_ = 0;
  Eigen::Vector3d dragStartPosition_ = Eigen::Vector3d::Zero();
  MouseEvent lastMouse_;
  WindowLevel dragStartWindowLevel_;
  MouseEvent dragStartMouse_;
  std::string cursorLine_, message_;
};

}  // namespace vesalius::picker
