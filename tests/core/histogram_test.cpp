// Histogram counts (core/histogram.h): bins of equal width from zero up to the largest value.
#include "vesalius/core/error.h"
#include "vesalius/core/histogram.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace vesalius {
namespace {

TEST(Histogram, CountsEachValueInItsBin) {
  Eigen::VectorXd values(7);
  values << 0.0, 0.1, 0.25, 0.49, 0.5, 1.3, -0.2;  // a bin's lower edge belongs to it; negatives to the first
  const std::vector<long> counts = histogramCounts(values, 0.25);
  EXPECT_EQ(counts, (std::vector<long>{3, 2, 1, 0, 0, 1}));
  EXPECT_EQ(std::accumulate(counts.begin(), counts.end(), 0L), values.size());
}

TEST(Histogram, RandomValuesAreAllCountedOnce) {
  for (const double width : {0.25, 1.0, 7.5}) {
    const Eigen::VectorXd values = (Eigen::VectorXd::Random(500).array() + 1.0) * 20.0;  // in [0, 40]
    const std::vector<long> counts = histogramCounts(values, width);
    EXPECT_EQ(std::accumulate(counts.begin(), counts.end(), 0L), 500) << width;
    EXPECT_EQ(long(counts.size()), long(std::floor(values.maxCoeff() / width)) + 1) << width;
    EXPECT_GT(counts.back(), 0) << width;  // the last bin holds the largest value
    for (std::size_t b = 0; b < counts.size(); ++b) {
      const double low = double(b) * width, high = double(b + 1) * width;
      const long inBin = long(((values.array() >= low) && (values.array() < high)).count());
      EXPECT_EQ(counts[b], inBin) << "bin " << b << " of width " << width;
    }
  }
}

TEST(Histogram, NonFiniteValuesAreNotCountedAndBadWidthsRefused) {
  Eigen::VectorXd values(3);
  values << 1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity();
  EXPECT_EQ(histogramCounts(values, 1.0), (std::vector<long>{0, 1}));
  EXPECT_TRUE(histogramCounts(Eigen::VectorXd(0), 1.0).empty());
  EXPECT_THROW(histogramCounts(values, 0.0), UsageError);
  EXPECT_THROW(histogramCounts(values, -1.0), UsageError);
}

}  // namespace
}  // namespace vesalius
