// Marker sets: the points a radiologist picks on a scan to drive fitting (Wang et al. 2021, §3.1, §4.1).
//
// Landmarks pair a scan point with a template point (by label, or by an explicit template position);
// ICP markers are scan points the deformed surface must pass through; attachments tie a template
// material point to a fixed world point. Positions are LPS millimetres.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace vesalius {

enum class MarkerKind { Landmark, IcpMarker, Attachment };
// As 3D Slicer's positionStatus (vtkMRMLMarkupsNode): "defined"; "undefined" (a named point not placed
// yet); "preview" (proposed, not accepted); "missing" (skipped: the point cannot be placed, e.g. outside
// the scan, and placing it is not asked for).
enum class MarkerStatus { Defined, Undefined, Preview, Missing };

const char* markerKindName(MarkerKind k);      // "landmark", "icp", "attachment"
const char* markerStatusName(MarkerStatus s);  // "defined", "undefined", "preview", "missing"
// Defined and preview markers have a position; undefined and missing ones do not.
bool hasPosition(MarkerStatus s);

struct Marker {
  std::string label;
  MarkerKind kind = MarkerKind::Landmark;
  MarkerStatus status = MarkerStatus::Defined;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // meaningless unless hasPosition(status)
  // For a landmark or attachment given with its template point: that point, in template space.
  std::optional<Eigen::Vector3d> templatePosition;
  std::string description;
  bool selected = true, locked = false, visible = true;
  // Carried between formats that have a place for them: the control point id and associated node of
  // 3D Slicer, the colour (RGB in [0, 1]) and tags of an ITK-SNAP annotation.
  std::string id, associatedNodeID;
  std::optional<Eigen::Vector3d> color;
  std::vector<std::string> tags;
};

struct MarkerSet {
  std::string name;
  std::vector<Marker> markers;

  std::size_t count(MarkerKind k) const;
  std::size_t countDefined() const;
  // Throws BadInput naming `source` on a non-finite position of a marker that has one, a non-finite
  // template position, or a colour outside [0, 1].
  void validate(const std::string& source) const;
};

}  // namespace vesalius
