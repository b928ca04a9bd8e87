// The markers being picked, with undo/redo of every edit and an autosave sidecar (issue 5).
//
// No VTK here: the document is the app's model, tested on its own. Every edit goes through one of the
// editing methods, becomes one entry of the undo stack, clears the redo stack, bumps revision() and, when
// an autosave path is set, rewrites the sidecar atomically so nothing is lost if the app dies.
//
// Suggestions: `vesalius markers suggest` writes ICP markers with status preview (3D Slicer's
// positionStatus) and "confidence C; ..." in their description. They stay preview, also in saved files,
// until the user accepts (defined) or rejects (deleted) them.
#pragma once

#include "vesalius/core/markers.h"

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace vesalius::picker {

class PickerDocument {
 public:
  // `restoredUnsaved`: the markers come from an autosave sidecar, so they count as unsaved edits.
  explicit PickerDocument(MarkerSet markers = {}, bool restoredUnsaved = false);

  const MarkerSet& markers() const { return markers_; }
  const Marker& marker(std::size_t index) const { return markers_.markers.at(index); }
  std::size_t size() const { return markers_.markers.size(); }
  // Changes on every edit, undo, redo and drag step: views redraw when it differs from what they drew.
  std::uint64_t revision() const { return revision_; }

  // ---- Edits (each one undo step) ----
  // Appends a defined marker labelled by nextLabel(kind); returns its index.
  std::size_t addMarker(MarkerKind kind, const Eigen::Vector3d& position);
  void moveMarker(std::size_t index, const Eigen::Vector3d& position);
  void removeMarker(std::size_t index);
  // Gives an undefined or missing (named, not placed) marker its position and makes it defined.
  void placeNamedMarker(std::size_t index, const Eigen::Vector3d& position);
  // Marks a named marker missing (skipped: 3D Slicer's "missing" position status).
  void markMissing(std::size_t index);
  // Makes preview marker `index` defined / deletes it. UsageError if it is not a preview.
  void acceptPreview(std::size_t index);
  void rejectPreview(std::size_t index);
  // Makes every preview marker of confidence >= `minConfidence` defined, all in one undo step; with
  // minConfidence <= 0 every preview, also those without a confidence. Returns how many.
  std::size_t acceptPreviews(double minConfidence = 0);
  std::size_t previewCount() const;

  // ---- Dragging: many position updates, one undo step ----
  // Moves marker `index` without recording; finishDrag records one move from where the drag began.
  void dragMarker(std::size_t index, const Eigen::Vector3d& position);
  void finishDrag(std::size_t index, const Eigen::Vector3d& dragStartPosition);

  bool canUndo() const { return !undoStack_.empty(); }
  bool canRedo() const { return !redoStack_.empty(); }
  bool undo();  // false when there is nothing to undo
  bool redo();

  // "L-3", "ICP-12", "A-1": the kind's prefix and one more than the highest number in use with it.
  std::string nextLabel(MarkerKind kind) const;

  // The placed (defined or preview), visible marker nearest to `point` within `maxDistance` mm that
  // `accept` (if given) accepts, e.g. only those on the slice shown.
  std::optional<std::size_t> nearestMarker(const Eigen::Vector3d& point, double maxDistance,
                                           const std::function<bool(const Marker&)>& accept = {}) const;

  // The first undefined landmark at or after `from` (wrapping around), i.e. the next name to place;
  // when none is left, the first missing (skipped) one, which is asked for again.
  std::optional<std::size_t> nextUndefinedLandmark(std::size_t from) const;

  // ---- Autosave ----
  // Where the sidecar goes; empty disables autosaving. Setting it does not write.
  void setAutosavePath(const std::string& path) { autosavePath_ = path; }
  // Writes the sidecar now (atomically, replacing the previous one) if there are unsaved edits.
  void autosave() const;
  // True when the markers differ from what was last saved (or loaded).
  bool hasUnsavedEdits() const { return savedRevision_ != revision_; }

  // Writes the markers to `path` (.mrk.json, LPS) atomically, replacing it only if `replace`; then the
  // autosave sidecar, now redundant, is removed.
  void save(const std::string& path, bool replace);

 private:
  // One edit of one slot: inserted (no before), erased (no after) or replaced.
  struct Edit {
    std::size_t index = 0;
    std::optional<Marker> before, after;
  };
  using Step = std::vector<Edit>;  // one undo step: its edits applied in order, undone in reverse
  void apply(const Step& step, bool forward);
  void record(const Step& step);  // applies, pushes, clears redo, autosaves
  void requirePreview(std::size_t index) const;
  void changed();

  MarkerSet markers_;
  std::vector<Step> undoStack_, redoStack_;
  std::uint64_t revision_ = 0;
  std::optional<std::uint64_t> savedRevision_;  // revision last saved or loaded; none: never saved
  std::string autosavePath_;
};

// The confidence in a suggestion's description ("confidence 0.812; edge ..."), if it has one.
std::optional<double> suggestionConfidence(const Marker& marker);

}  // namespace vesalius::picker
