// Otsu's thresholds by exhaustive search over a histogram (otsu.h).
#include "vesalius/segmentation/otsu.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vesalius::segmentation {
namespace {

// Prefix sums of counts and of count * bin centre, so a class of bins [a, b) has size n[b] - n[a].
struct Histogram {
  std::vector<double> n, sum;
  double lo = 0, width = 1;

  double score(int a, int b) const {  // w mu^2 of the class [a, b), up to the constant total
    const double w = n[b] - n[a];
    return w > 0 ? (sum[b] - sum[a]) * (sum[b] - sum[a]) / w : 0.0;
  }
};

Histogram histogramOf(const Grid<float>& image, const Mask* within, int bins) {
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < image.values.size(); ++i)
    if ((!within || within->values[i]) && std::isfinite(image.values[i])) {
      lo = std::min(lo, image.values[i]);
      hi = std::max(hi, image.values[i]);
    }
  if (!(lo < hi)) throw BadInput("", "Otsu's threshold needs at least two distinct values");
  Histogram h;
  h.lo = lo;
  h.width = (double(hi) - lo) / bins;
  std::vector<double> count(bins, 0.0);
  for (std::size_t i = 0; i < image.values.size(); ++i)
    if ((!within || within->values[i]) && std::isfinite(image.values[i]))
      ++count[std::min(bins - 1, int((image.values[i] - h.lo) / h.width))];
  h.n.assign(bins + 1, 0.0);
  h.sum.assign(bins + 1, 0.0);
  for (int b = 0; b < bins; ++b) {
    h.n[b + 1] = h.n[b] + count[b];
    h.sum[b + 1] = h.sum[b] + count[b] * (h.lo + (b + 0.5) * h.width);
  }
  return h;
}

// The best split of bins [first, bins) into `classes` classes: its score and the class starts.
double bestSplit(const Histogram& h, int first, int classes, std::vector<int>& starts) {
  const int bins = int(h.n.size()) - 1;
  if (classes == 1) return h.score(first, bins);
  double best = -1;
  std::vector<int> rest, bestRest;
  for (int cut = first + 1; cut <= bins - classes + 1; ++cut) {
    const double s = h.score(first, cut) + bestSplit(h, cut, classes - 1, rest);
    if (s > best) {
      best = s;
      bestRest = rest;
      bestRest.insert(bestRest.begin(), cut);
    }
  }
  starts = bestRest;
  return best;
}

}  // namespace

std::vector<float> otsuThresholds(const Grid<float>& image, const Mask* within, const OtsuOptions& options) {
  if (options.classes < 2 || options.classes > 4 || options.bins < options.classes)
    throw UsageError("Otsu's method needs 2 to 4 classes and at least as many bins");
  if (within && within->values.size() != image.values.size())
    throw UsageError("Otsu's method: the mask and the image have different sizes");
  const Histogram h = histogramOf(image, within, options.bins);
  std::vector<int> starts;
  bestSplit(h, 0, options.classes, starts);
  std::vector<float> thresholds;
  for (int b : starts) thresholds.push_back(float(h.lo + b * h.width));
  return thresholds;
}

}  // namespace vesalius::segmentation
