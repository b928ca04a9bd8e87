#include "vesalius/core/histogram.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vesalius {

std::vector<long> histogramCounts(const Eigen::VectorXd& values, double binWidth) {
  if (!(binWidth > 0)) throw UsageError("histogram: the bin width must be positive");
  double largest = -1;
  for (double v : values)
    if (std::isfinite(v)) largest = std::max(largest, std::max(v, 0.0));
  if (largest < 0) return {};
  std::vector<long> counts(std::size_t(largest / binWidth) + 1, 0);
  for (double v : values)
    if (std::isfinite(v)) ++counts[std::size_t(std::max(v, 0.0) / binWidth)];
  return counts;
}

}  // namespace vesalius
