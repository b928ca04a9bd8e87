// A histogram of values drawn as a panel of bars with its title, count, mean and maximum, to stand beside
// the slices of a picture (vesalius fit: the ICP marker errors after the fit, as Wang et al.'s Fig. 16 plots them).
#pragma once

#include "vesalius/viz/rgb_image.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::viz {

struct HistogramPanelOptions {
  std::string title;              // the first line
  std::string items = "values";   // what is counted: "<n> <items>, mean .., max .." and "<items> per <bin> bin"
  std::string unit = "mm";        // of the values, printed with two decimals
  double binWidth = 1.0;          // in `unit`; bins [0, w), [w, 2w), ... (core/histogram.h)
  int maxBars = 80;               // the last bar then holds everything beyond, and the axis says ">"
  int width = 380, height = 400;  // pixels; the bars take what the text leaves
  Rgb background{{0, 0, 0}};
  Rgb text{{235, 235, 235}}, bar{{60, 220, 90}}, axis{{150, 150, 150}};
};

// values: #N, finite. Throws UsageError for no values, a non-finite value, a bin width that is not positive,
// maxBars below 1 or a panel smaller than 1 pixel.
RgbImage histogramPanel(const Eigen::VectorXd& values, const HistogramPanelOptions& options);

}  // namespace vesalius::viz
