// Counts of values in bins of equal width from zero, as reports list them and pictures draw them.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace vesalius {

// Counts of `values` (#N) in the bins [0, w), [w, 2w), ... up to the bin of the largest value; a negative
// value counts in the first bin; a value that is not finite is not counted. Empty for no finite values.
// Throws UsageError unless binWidth > 0.
std::vector<long> histogramCounts(const Eigen::VectorXd& values, double binWidth);

}  // namespace vesalius
