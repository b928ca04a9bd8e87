// Otsu's thresholds with known answers: separated value clusters must be split between the clusters,
// and the mask must restrict which voxels count.
#include "vesalius/segmentation/otsu.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

namespace vesalius::segmentation {
namespace {

// 1000 voxels: 200 at 10, 500 at 60 +- 2, 300 at 200.
Grid<float> threeClusters() {
  Grid<float> g(GridGeometry{Eigen::Vector3i(10, 10, 10)});
  for (std::size_t n = 0; n < g.values.size(); ++n)
    g.values[n] = n < 200 ? 10.0f : n < 700 ? 58.0f + float(n % 5) : 200.0f;
  return g;
}

TEST(Otsu, TwoClassesSplitBetweenTheGroups) {
  const std::vector<float> t = otsuThresholds(threeClusters());
  ASSERT_EQ(t.size(), 1u);
  // Between-class variance is largest splitting {10, 60} from {200}: 0.7*0.3*(45.7-200)^2 = 5000 against
  // 0.2*0.8*(10-112.5)^2 = 1681 for {10} | {60, 200}.
  EXPECT_GT(t[0], 62.0f);
  EXPECT_LE(t[0], 200.0f);
}

TEST(Otsu, ThreeClassesFindEachCluster) {
  const std::vector<float> t = otsuThresholds(threeClusters(), nullptr, OtsuOptions{3, 256});
  ASSERT_EQ(t.size(), 2u);
  EXPECT_GT(t[0], 10.0f);
  EXPECT_LE(t[0], 58.0f);
  EXPECT_GT(t[1], 62.0f);
  EXPECT_LE(t[1], 200.0f);
}

TEST(Otsu, MaskRestrictsTheVoxels) {
  const Grid<float> g = threeClusters();
  Mask lowTwo(g.geometry, 0);
  for (std::size_t n = 0; n < 700; ++n) lowTwo.values[n] = 1;
  const std::vector<float> t = otsuThresholds(g, &lowTwo);
  EXPECT_GT(t[0], 10.0f);
  EXPECT_LE(t[0], 58.0f);
}

TEST(Otsu, RejectsConstantValuesAndBadOptions) {
  const Grid<float> flat(GridGeometry{Eigen::Vector3i(4, 4, 4)}, 3.0f);
  EXPECT_THROW(otsuThresholds(flat), BadInput);
  EXPECT_THROW(otsuThresholds(threeClusters(), nullptr, OtsuOptions{5, 256}), UsageError);
  const Mask wrongSize(GridGeometry{Eigen::Vector3i(2, 2, 2)}, 1);
  EXPECT_THROW(otsuThresholds(threeClusters(), &wrongSize), UsageError);
}

}  // namespace
}  // namespace vesalius::segmentation
