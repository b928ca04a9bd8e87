#include "vesalius/core/markers.h"

#include "vesalius/core/error.h"

#include <algorithm>

namespace vesalius {

const char* markerKindName(MarkerKind k) {
  switch (k) {
    case MarkerKind::Landmark: return "landmark";
    case MarkerKind::IcpMarker: return "icp";
    case MarkerKind::Attachment: return "attachment";
  }
  return "landmark";
}

const char* markerStatusName(MarkerStatus s) {
  switch (s) {
    case MarkerStatus::Defined: return "defined";
    case MarkerStatus::Undefined: return "undefined";
    case MarkerStatus::Preview: return "preview";
    case MarkerStatus::Missing: return "missing";
  }
  return "defined";
}

bool hasPosition(MarkerStatus s) { return s == MarkerStatus::Defined || s == MarkerStatus::Preview; }

std::size_t MarkerSet::count(MarkerKind k) const {
  return std::count_if(markers.begin(), markers.end(), [k](const Marker& m) { return m.kind == k; });
}

std::size_t MarkerSet::countDefined() const {
  return std::count_if(markers.begin(), markers.end(),
                       [](const Marker& m) { return m.status == MarkerStatus::Defined; });
}

void MarkerSet::validate(const std::string& source) const {
  for (std::size_t i = 0; i < markers.size(); ++i) {
    const Marker& m = markers[i];
    if (hasPosition(m.status) && !m.position.allFinite())
      throw BadInput(source, "marker " + std::to_string(i + 1) + " ('" + m.label + "') has a non-finite position");
    if (m.templatePosition && !m.templatePosition->allFinite())
      throw BadInput(source, "marker " + std::to_string(i + 1) + " ('" + m.label +
                                 "') has a non-finite template position");
    if (m.color && !(m.color->array() >= 0.0 && m.color->array() <= 1.0).all())
      throw BadInput(source, "marker " + std::to_string(i + 1) + " ('" + m.label +
                                 "') has a colour outside [0, 1]");
  }
}

}  // namespace vesalius
