// Landmarks paired by label (core/landmark_pairs.h): pairs in the first set's order, pairs with a point not
// placed skipped, and a label used twice or without a partner refused naming the set it is in.
#include "vesalius/core/landmark_pairs.h"

#include "expect_bad_input.h"

#include <gtest/gtest.h>

namespace vesalius {
namespace {

Marker marker(const std::string& label, MarkerKind kind, double x, MarkerStatus status = MarkerStatus::Defined) {
  Marker m;
  m.label = label;
  m.kind = kind;
  m.status = status;
  m.position = Eigen::Vector3d(x, 2 * x, 3 * x);
  return m;
}

MarkerSet setOf(std::vector<Marker> markers) {
  MarkerSet set;
  set.markers = std::move(markers);
  return set;
}

TEST(LandmarkPairs, PairedByLabelInTheFirstSetsOrder) {
  // The scan's landmarks in another order, one of them not placed yet, and an ICP marker that is no landmark.
  const MarkerSet templ = setOf({marker("tip", MarkerKind::Landmark, 1), marker("notch", MarkerKind::Landmark, 2),
                                 marker("hilum", MarkerKind::Landmark, 3), marker("dome", MarkerKind::Landmark, 4)});
  const MarkerSet scan = setOf({marker("dome", MarkerKind::Landmark, 40), marker("icp-1", MarkerKind::IcpMarker, 9),
                                marker("tip", MarkerKind::Landmark, 10),
                                marker("notch", MarkerKind::Landmark, 0, MarkerStatus::Undefined),
                                marker("hilum", MarkerKind::Landmark, 30)});
  const LandmarkPairs pairs = pairLandmarks(templ, "template.mrk.json", scan, "scan.mrk.json");
  EXPECT_EQ(pairs.labels, (std::vector<std::string>{"tip", "hilum", "dome"}));
  EXPECT_EQ(pairs.skipped, 1);
  ASSERT_EQ(pairs.first.rows(), 3);
  ASSERT_EQ(pairs.second.rows(), 3);
  const double firstX[] = {1, 3, 4}, secondX[] = {10, 30, 40};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(pairs.first.row(k), Eigen::RowVector3d(firstX[k], 2 * firstX[k], 3 * firstX[k])) << k;
    EXPECT_EQ(pairs.second.row(k), Eigen::RowVector3d(secondX[k], 2 * secondX[k], 3 * secondX[k])) << k;
  }
  EXPECT_EQ(markersOfKind(scan, MarkerKind::Landmark).size(), 4u);
  EXPECT_EQ(markersOfKind(scan, MarkerKind::IcpMarker).front()->label, "icp-1");
}

TEST(LandmarkPairs, UnpairableLabelsNameTheirSet) {
  const MarkerSet ab = setOf({marker("a", MarkerKind::Landmark, 1), marker("b", MarkerKind::Landmark, 2)});
  const MarkerSet a = setOf({marker("a", MarkerKind::Landmark, 1)});
  const MarkerSet aa = setOf({marker("a", MarkerKind::Landmark, 1), marker("a", MarkerKind::Landmark, 2)});
  test::expectOneLineBadInput("first.csv", "landmark 'b' has no partner in second.csv",
                              [&] { pairLandmarks(ab, "first.csv", a, "second.csv"); });
  test::expectOneLineBadInput("second.csv", "landmark 'b' has no partner in first.csv",
                              [&] { pairLandmarks(a, "first.csv", ab, "second.csv"); });
  test::expectOneLineBadInput("second.csv", "landmark label 'a' is used twice",
                              [&] { pairLandmarks(a, "first.csv", aa, "second.csv"); });
}

}  // namespace
}  // namespace vesalius
