#include "picker_document.h"

#include "vesalius/core/error.h"
#include "vesalius/io/marker_io.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

namespace vesalius::picker {
namespace {

const char* labelPrefix(MarkerKind kind) {
  switch (kind) {
    case MarkerKind::Landmark: return "L-";
    case MarkerKind::IcpMarker: return "ICP-";
    case MarkerKind::Attachment: return "A-";
  }
  return "M-";
}

// The number after `prefix` in `label`, or 0 when the label is not prefix + digits.
long labelNumber(const std::string& label, const std::string& prefix) {
  if (label.size() <= prefix.size() || label.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string digits = label.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) return 0;
  return std::strtol(digits.c_str(), nullptr, 10);
}

}  // namespace

PickerDocument::PickerDocument(MarkerSet markers, bool restoredUnsaved) : markers_(std::move(markers)) {
  if (!restoredUnsaved) savedRevision_ = revision_;
}

std::size_t PickerDocument::addMarker(MarkerKind kind, const Eigen::Vector3d& position) {
  Marker marker;
  marker.label = nextLabel(kind);
  marker.kind = kind;
  marker.position = position;
  const std::size_t index = markers_.markers.size();
  record({{index, std::nullopt, marker}});
  return index;
}

void PickerDocument::moveMarker(std::size_t index, const Eigen::Vector3d& position) {
  Marker moved = marker(index);
  moved.position = position;
  record({{index, marker(index), moved}});
}

void PickerDocument::removeMarker(std::size_t index) { record({{index, marker(index), std::nullopt}}); }

void PickerDocument::placeNamedMarker(std::size_t index, const Eigen::Vector3d& position) {
  Marker placed = marker(index);
  placed.status = MarkerStatus::Defined;
  placed.position = position;
  record({{index, marker(index), placed}});
}

void PickerDocument::markMissing(std::size_t index) {
  Marker missing = marker(index);
  missing.status = MarkerStatus::Missing;
  record({{index, marker(index), missing}});
}

void PickerDocument::requirePreview(std::size_t index) const {
  if (marker(index).status != MarkerStatus::Preview)
    throw UsageError("marker " + marker(index).label + " is not a suggestion (preview) to accept or reject");
}

void PickerDocument::acceptPreview(std::size_t index) {
  requirePreview(index);
  Marker accepted = marker(index);
  accepted.status = MarkerStatus::Defined;
  record({{index, marker(index), accepted}});
}

void PickerDocument::rejectPreview(std::size_t index) {
  requirePreview(index);
  removeMarker(index);
}

std::size_t PickerDocument::acceptPreviews(double minConfidence) {
  Step step;
  for (std::size_t i = 0; i < markers_.markers.size(); ++i) {
    const Marker& m = markers_.markers[i];
    if (m.status != MarkerStatus::Preview) continue;
    if (minConfidence > 0 && suggestionConfidence(m).value_or(0) < minConfidence) continue;
    Marker accepted = m;
    accepted.status = MarkerStatus::Defined;
    step.push_back({i, m, accepted});
  }
  if (!step.empty()) record(step);
  return step.size();
}

std::size_t PickerDocument::previewCount() const {
  return std::size_t(std::count_if(markers_.markers.begin(), markers_.markers.end(),
                                   [](const Marker& m) { return m.status == MarkerStatus::Preview; }));
}

void PickerDocument::dragMarker(std::size_t index, const Eigen::Vector3d& position) {
  markers_.markers.at(index).position = position;
  ++revision_;
}

void PickerDocument::finishDrag(std::size_t index, const Eigen::Vector3d& dragStartPosition) {
  Marker before = marker(index);
  before.position = dragStartPosition;
  const Marker after = marker(index);
  markers_.markers[index] = before;
  record({{index, before, after}});
}

bool PickerDocument::undo() {
  if (undoStack_.empty()) return false;
  const Step step = undoStack_.back();
  undoStack_.pop_back();
  apply(step, false);
  redoStack_.push_back(step);
  autosave();
  return true;
}

bool PickerDocument::redo() {
  if (redoStack_.empty()) return false;
  const Step step = redoStack_.back();
  redoStack_.pop_back();
  apply(step, true);
  undoStack_.push_back(step);
  autosave();
  return true;
}

void PickerDocument::apply(const Step& step, bool forward) {
  auto& list = markers_.markers;
  for (std::size_t i = 0; i < step.size(); ++i) {
    const Edit& edit = forward ? step[i] : step[step.size() - 1 - i];
    const std::optional<Marker>& from = forward ? edit.before : edit.after;
    const std::optional<Marker>& to = forward ? edit.after : edit.before;
    if (!from) {
      list.insert(list.begin() + std::ptrdiff_t(edit.index), *to);
    } else if (!to) {
      list.erase(list.begin() + std::ptrdiff_t(edit.index));
    } else {
      list.at(edit.index) = *to;
    }
  }
  changed();
}

void PickerDocument::record(const Step& step) {
  apply(step, true);
  undoStack_.push_back(step);
  redoStack_.clear();
  autosave();
}

void PickerDocument::changed() { ++revision_; }

std::string PickerDocument::nextLabel(MarkerKind kind) const {
  const std::string prefix = labelPrefix(kind);
  long highest = 0;
  for (const Marker& m : markers_.markers) highest = std::max(highest, labelNumber(m.label, prefix));
  return prefix + std::to_string(highest + 1);
}

std::optional<std::size_t> PickerDocument::nearestMarker(const Eigen::Vector3d& point,
                                                         double maxDistance,
                                                         const std::function<bool(const Marker&)>& accept) const {
  std::optional<std::size_t> nearest;
  double nearestDistance = maxDistance;
  for (std::size_t i = 0; i < markers_.markers.size(); ++i) {
    const Marker& m = markers_.markers[i];
    if (!hasPosition(m.status) || !m.visible || (accept && !accept(m))) continue;
    const double distance = (m.position - point).norm();
    if (distance <= nearestDistance) {
      nearest = i;
      nearestDistance = distance;
    }
  }
  return nearest;
}

std::optional<std::size_t> PickerDocument::nextUndefinedLandmark(std::size_t from) const {
  const std::size_t n = markers_.markers.size();
  for (MarkerStatus wanted : {MarkerStatus::Undefined, MarkerStatus::Missing})
    for (std::size_t step = 0; step < n; ++step) {
      const Marker& m = markers_.markers[(from + step) % n];
      if (m.kind == MarkerKind::Landmark && m.status == wanted) return (from + step) % n;
    }
  return std::nullopt;
}

void PickerDocument::autosave() const {
  if (autosavePath_.empty() || !hasUnsavedEdits()) return;
  WriteOptions replace;
  replace.force = true;
  io::writeMarkers(autosavePath_, markers_, replace);
}

void PickerDocument::save(const std::string& path, bool replace) {
  WriteOptions options;
  options.force = replace;
  io::writeMarkers(path, markers_, options);
  savedRevision_ = revision_;
  if (!autosavePath_.empty()) {
    std::error_code ignored;  // a sidecar that is already gone is what we want
    std::filesystem::remove(autosavePath_, ignored);
  }
}

std::optional<double> suggestionConfidence(const Marker& marker) {
  static const std::string kKey = "confidence ";
  const std::size_t at = marker.description.find(kKey);
  if (at == std::string::npos) return std::nullopt;
  const char* start = marker.description.c_str() + at + kKey.size();
  char* end = nullptr;
  const double confidence = std::strtod(start, &end);
  if (end == start || !std::isfinite(confidence)) return std::nullopt;
  return confidence;
}

}  // namespace vesalius::picker
