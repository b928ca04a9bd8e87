// Marker sets: the points a radiologist picks on a scan to drive fitting (seed 002 §3.1, §4.1).
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
// As 3D Slicer's positionStatus: "defined", "undefined" (a named point not placed yet), "preview".
enum class MarkerStatus { Defined, Undefined, Preview };

const char* markerKindName(MarkerKind k);      // "landmark", "icp", "attachment"
const char* markerStatusName(MarkerStatus s);  // "defined", "undefined", "preview"

struct Marker {
  std::string label;
  MarkerKind kind = MarkerKind::Landmark;
  MarkerStatus status = MarkerStatus::Defined;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // meaningless when status is Undefined
  // For a landmark or attachment given with its template point: that point, in template space.
  std::optional<Eigen::Vector3d> templatePosition;
  std::string description;
  bool selected = true, locked = false, visible = true;
};

struct MarkerSet {
  std::string name;
  std::vector<Marker> markers;

  std::size_t count(MarkerKind k) const;
  std::size_t countDefined() const;
  // Throws BadInput naming `source` on a non-finite position of a defined marker.
  void validate(const std::string& source) const;
};

}  // namespace vesalius
