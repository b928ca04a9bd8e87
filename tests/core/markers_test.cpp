// MarkerSet: names of kinds and states, counts, validation of defined positions.
#include "vesalius/core/error.h"
#include "vesalius/core/markers.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace vesalius {
namespace {

Marker marker(MarkerKind kind, MarkerStatus status, double x) {
  Marker m;
  m.kind = kind;
  m.status = status;
  m.position = Eigen::Vector3d(x, 2 * x, 3 * x);
  return m;
}

TEST(MarkerSet, KindAndStatusNames) {
  EXPECT_STREQ(markerKindName(MarkerKind::Landmark), "landmark");
  EXPECT_STREQ(markerKindName(MarkerKind::IcpMarker), "icp");
  EXPECT_STREQ(markerKindName(MarkerKind::Attachment), "attachment");
  EXPECT_STREQ(markerStatusName(MarkerStatus::Defined), "defined");
  EXPECT_STREQ(markerStatusName(MarkerStatus::Undefined), "undefined");
  EXPECT_STREQ(markerStatusName(MarkerStatus::Preview), "preview");
  EXPECT_STREQ(markerStatusName(MarkerStatus::Missing), "missing");
  EXPECT_TRUE(hasPosition(MarkerStatus::Defined));
  EXPECT_TRUE(hasPosition(MarkerStatus::Preview));
  EXPECT_FALSE(hasPosition(MarkerStatus::Undefined));
  EXPECT_FALSE(hasPosition(MarkerStatus::Missing));
}

TEST(MarkerSet, CountsByKindAndDefinedState) {
  MarkerSet s;
  s.markers = {marker(MarkerKind::Landmark, MarkerStatus::Defined, 1),
               marker(MarkerKind::IcpMarker, MarkerStatus::Defined, 2),
               marker(MarkerKind::IcpMarker, MarkerStatus::Undefined, 0),
               marker(MarkerKind::IcpMarker, MarkerStatus::Preview, 3),
               marker(MarkerKind::Attachment, MarkerStatus::Defined, 4)};
  EXPECT_EQ(s.count(MarkerKind::Landmark), 1u);
  EXPECT_EQ(s.count(MarkerKind::IcpMarker), 3u);
  EXPECT_EQ(s.count(MarkerKind::Attachment), 1u);
  EXPECT_EQ(s.countDefined(), 3u);
}

TEST(MarkerSet, ValidateRejectsNonFiniteDefinedPositionsOnly) {
  MarkerSet s;
  s.markers = {marker(MarkerKind::Landmark, MarkerStatus::Defined, 1),
               marker(MarkerKind::Landmark, MarkerStatus::Undefined, 0),
               marker(MarkerKind::Landmark, MarkerStatus::Missing, 0)};
  s.markers[1].position.x() = std::numeric_limits<double>::quiet_NaN();
  s.markers[2].position.y() = std::numeric_limits<double>::infinity();
  EXPECT_NO_THROW(s.validate("points.mrk.json"));
  s.markers[1].color = Eigen::Vector3d(0.5, 1.0, 0.0);
  EXPECT_NO_THROW(s.validate("points.mrk.json"));
  s.markers[1].color = Eigen::Vector3d(0.5, 255.0, 0.0);
  EXPECT_THROW(s.validate("points.mrk.json"), BadInput);
  s.markers[1].color.reset();
  s.markers[0].position.z() = std::numeric_limits<double>::infinity();
  try {
    s.validate("points.mrk.json");
    ADD_FAILURE() << "validate accepted an infinite position";
  } catch (const BadInput& e) {
    EXPECT_EQ(e.file(), "points.mrk.json");
    EXPECT_NE(std::string(e.what()).find("points.mrk.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace vesalius
