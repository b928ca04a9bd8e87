// Histogram panels (viz/histogram_panel.h): one bar per bin, as tall as its count against the largest, and
// bins beyond the last bar counted in it.
#include "vesalius/viz/histogram_panel.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <vector>

namespace vesalius::viz {
namespace {

struct Bar {
  int left = 0, right = 0, height = 0;  // columns [left, right], pixels of bar colour in its tallest column
};

// The bars: runs of columns holding the bar colour, left to right.
std::vector<Bar> barsOf(const RgbImage& panel, const Rgb& colour) {
  std::vector<Bar> bars;
  bool inside = false;
  for (int x = 0; x < panel.width; ++x) {
    int height = 0;
    for (int y = 0; y < panel.height; ++y) height += panel.get(x, y) == colour;
    if (height == 0) {
      inside = false;
      continue;
    }
    if (!inside) bars.push_back({x, x, 0});
    inside = true;
    bars.back().right = x;
    bars.back().height = std::max(bars.back().height, height);
  }
  return bars;
}

TEST(HistogramPanel, OneBarPerBinAsTallAsItsCount) {
  HistogramPanelOptions options;
  options.title = "errors";
  options.binWidth = 0.25;
  for (const int height : {300, 500}) {
    options.height = height;
    Eigen::VectorXd values(8);
    values << 0.1, 0.1, 0.2, 0.05, 0.3, 0.6, 0.7, 0.55;  // counts 4, 1, 3
    const RgbImage panel = histogramPanel(values, options);
    EXPECT_EQ(panel.width, options.width);
    EXPECT_EQ(panel.height, height);
    EXPECT_EQ(panel.get(0, 0), options.background);
    const std::vector<Bar> bars = barsOf(panel, options.bar);
    ASSERT_EQ(bars.size(), 3u) << height;
    const double tallest = bars[0].height;
    std::cout << height << " pixels: bars " << bars[0].height << ", " << bars[1].height << ", " << bars[2].height
              << " pixels tall\n";
    EXPECT_NEAR(bars[1].height / tallest, 0.25, 1.0 / tallest);
    EXPECT_NEAR(bars[2].height / tallest, 0.75, 1.0 / tallest);
    // Bars of one width, side by side across the panel's width.
    EXPECT_LE(std::abs((bars[1].right - bars[1].left) - (bars[0].right - bars[0].left)), 1);
    EXPECT_GT(bars[2].right - bars[0].left, options.width / 2);
  }
}

TEST(HistogramPanel, BinsBeyondTheLastBarAreCountedInIt) {
  HistogramPanelOptions options;
  options.binWidth = 0.25;
  options.height = 600;
  for (const int maxBars : {20, 80}) {
    options.maxBars = maxBars;
    Eigen::VectorXd values(200);  // one value in each of 200 bins
    for (int k = 0; k < 200; ++k) values[k] = 0.125 + 0.25 * k;
    const std::vector<Bar> bars = barsOf(histogramPanel(values, options), options.bar);
    ASSERT_EQ(int(bars.size()), maxBars);
    // The last bar holds 200 - (maxBars - 1) values, the others one each.
    const double last = 200 - (maxBars - 1);
    std::cout << maxBars << " bars: the last " << bars.back().height << " pixels, the first " << bars.front().height
              << '\n';
    EXPECT_NEAR(bars.front().height, bars.back().height / last, 1.0);
  }
}

TEST(HistogramPanel, UnusableValuesAndOptionsAreRefused) {
  HistogramPanelOptions options;
  EXPECT_THROW(histogramPanel(Eigen::VectorXd(0), options), UsageError);
  Eigen::VectorXd values(2);
  values << 1.0, std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(histogramPanel(values, options), UsageError);
  values[1] = 2.0;
  options.maxBars = 0;
  EXPECT_THROW(histogramPanel(values, options), UsageError);
  options.maxBars = 80;
  options.binWidth = 0;
  EXPECT_THROW(histogramPanel(values, options), UsageError);
}

}  // namespace
}  // namespace vesalius::viz
