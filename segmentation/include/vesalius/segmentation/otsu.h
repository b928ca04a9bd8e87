// Otsu's threshold selection, with two or more classes.
//
// Method: N. Otsu, "A threshold selection method from gray-level histograms", IEEE Trans. SMC 9(1), 1979,
// extended to several classes as in Liao, Chen and Chung, "A fast algorithm for multilevel thresholding",
// J. Inf. Sci. Eng. 17, 2001: the values are binned into a histogram over their range and the thresholds
// are the bin edges that maximise the between-class variance, sum_k w_k mu_k^2 (w_k the class sizes,
// mu_k the class means), found by exhaustive search over prefix sums (bins^(classes-1) candidates).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/segmentation/label_ops.h"

#include <vector>

namespace vesalius::segmentation {

struct OtsuOptions {
  int classes = 2;  // 2..4; the result holds classes - 1 thresholds
  int bins = 256;
};

// Increasing thresholds t_1 < ... < t_{classes-1} of the values of `image` inside `within` (every voxel
// when `within` is null): class k holds the values in [t_k, t_{k+1}). Throws BadInput if fewer than two
// distinct values are present, UsageError on bad options or a mask of another size.
std::vector<float> otsuThresholds(const Grid<float>& image, const Mask* within = nullptr,
                                  const OtsuOptions& options = {});

}  // namespace vesalius::segmentation
