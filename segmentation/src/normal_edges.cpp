// Edge search along surface normals (normal_edges.h). ITK only through gaussianSmoothMm, so this file
// builds as plain C++.
#include "vesalius/segmentation/normal_edges.h"

#include "mri_stages.h"
#include "vesalius/core/error.h"
#include "vesalius/core/grid_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace vesalius::segmentation {
namespace {

void validate(const MatrixX3d& points, const MatrixX3d& normals, const NormalEdgeOptions& o) {
  for (double v : {o.sigmaMm, o.searchMm, o.stepMm})
    if (!(v > 0) || !std::isfinite(v)) throw UsageError("edge search: sigma, search and step must be positive mm");
  if (!(o.sideMm >= 0) || !(o.bandMads > 0) || !(o.contrastMads >= 0) || !std::isfinite(o.contrastMads))
    throw UsageError("edge search: side, band and contrast must be positive");
  if (!(o.plateauMm >= 0) || !std::isfinite(o.plateauMm) || !(o.plateauMads >= 0) || !std::isfinite(o.plateauMads))
    throw UsageError("edge search: the plateau's reach and tolerance must not be negative");
  if (o.stepMm > o.searchMm) throw UsageError("edge search: the step must not exceed the search distance");
  if (points.rows() != normals.rows()) throw UsageError("edge search: one normal per point is needed");
  for (Eigen::Index i = 0; i < normals.rows(); ++i)
    if (!(normals.row(i).norm() > 0) || !points.row(i).allFinite())
      throw UsageError("edge search: point " + std::to_string(i) + " has no normal or no position");
}

// The part of `scan` within `marginMm` of the points' bounding box (in index space), so that blurring
// costs the organ's neighbourhood, not the whole scan. The direction is orthonormal up to round-off, so
// r mm moves an index by at most r / spacing along each axis.
Image cropAround(const Image& scan, const MatrixX3d& points, double marginMm) {
  const GridGeometry& g = scan.geometry;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d index = g.worldToIndex(points.row(i).transpose());
    low = low.cwiseMin(index);
    high = high.cwiseMax(index);
  }
  Eigen::Vector3i first, last;
  for (int a = 0; a < 3; ++a) {
    const double margin = marginMm / g.spacing[a] + 1;
    first[a] = int(std::clamp(std::floor(low[a] - margin), 0.0, double(g.size[a] - 1)));
    last[a] = int(std::clamp(std::ceil(high[a] + margin), double(first[a]), double(g.size[a] - 1)));
  }
  GridGeometry c = g;
  c.size = last - first + Eigen::Vector3i::Ones();
  c.origin = g.indexToWorld(first.cast<double>());
  Image out(c);
  out.fileType = scan.fileType;
  for (int k = 0; k < c.size.z(); ++k)
    for (int j = 0; j < c.size.y(); ++j)
      for (int i = 0; i < c.size.x(); ++i) out.at(i, j, k) = scan.at(first.x() + i, first.y() + j, first.z() + k);
  return out;
}

// Trilinear value at a world point; nothing outside the box of voxel centres (no extrapolated edges).
// The blurred scan at a world point; nothing beyond its outermost voxel centres.
std::optional<double> valueAt(const Grid<float>& grid, const Eigen::Vector3d& world) {
  const Eigen::Vector3d index = grid.geometry.worldToIndex(world);
  for (int a = 0; a < 3; ++a)
    if (!(index[a] >= 0 && index[a] <= grid.geometry.size[a] - 1)) return std::nullopt;
  return sampleTrilinear(grid, index);
}

// The blurred scan along the normal and its derivative: derivative[k] is ∂I/∂n at s_k = -searchMm +
// k stepMm, the difference of the blurred scan at s_k ± stepMm / 2; values reach sideMm further both ways,
// so that values[k] lies about sideMm inside s_k and values[k + 2 side + 1] as far outside it. Empty when
// any of these samples falls outside the scan. The plateaus reach plateauMm further: at(j) for j < 0 lies
// |j| steps behind values[0], for j past the end as far beyond values.back(); NaN beyond the scan, where
// the plateau is not checked.
struct Profile {
  std::vector<double> values, derivative, behind, beyond;
  int side = 0;       // sideMm in steps
  double noise = 0;   // derivatives up to this are round-off of the blur, not edges
  double inner(int k) const { return values[std::size_t(k)]; }
  double outer(int k) const { return values[std::size_t(k + 2 * side + 1)]; }
  int plateau() const { return int(behind.size()); }
  double at(int j) const {
    if (j < 0) return behind[std::size_t(-j - 1)];
    if (j >= int(values.size())) return beyond[std::size_t(j - int(values.size()))];
    return values[std::size_t(j)];
  }
};

// The blurred scan at p + s n, NaN beyond the scan.
double valueOrNan(const Grid<float>& blurred, const Eigen::Vector3d& p, const Eigen::Vector3d& n, double s) {
  return valueAt(blurred, p + n * s).value_or(std::numeric_limits<double>::quiet_NaN());
}

Profile sampleProfile(const Grid<float>& blurred, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                      const NormalEdgeOptions& o) {
  Profile profile;
  profile.side = int(std::lround(o.sideMm / o.stepMm));
  const int pad = profile.side, count = 2 * int(std::lround(o.searchMm / o.stepMm)) + 1;
  const double first = -o.searchMm - (pad + 0.5) * o.stepMm;  // s of values[0]
  for (int j = 0; j < count + 1 + 2 * pad; ++j) {
    const std::optional<double> v = valueAt(blurred, p + n * (first + j * o.stepMm));
    if (!v) return {};
    profile.values.push_back(*v);
    profile.noise = std::max(profile.noise, 1e-5 * (1 + std::abs(*v)) / o.stepMm);
  }
  for (int k = 0; k < count; ++k)
    profile.derivative.push_back((profile.values[std::size_t(k + pad + 1)] - profile.values[std::size_t(k + pad)]) /
                                 o.stepMm);
  const double last = first + double(profile.values.size() - 1) * o.stepMm;
  for (int j = 1; j <= int(std::lround(o.plateauMm / o.stepMm)); ++j) {
    profile.behind.push_back(valueOrNan(blurred, p, n, first - j * o.stepMm));
    profile.beyond.push_back(valueOrNan(blurred, p, n, last + j * o.stepMm));
  }
  return profile;
}

double edgeValue(double derivative, EdgePolarity polarity) {
  if (polarity == EdgePolarity::Falling) return -derivative;
  if (polarity == EdgePolarity::Rising) return derivative;
  return std::abs(derivative);
}

// The organ's intensity: a value within [low, high] is taken for the organ's tissue; deviation is its
// robust standard deviation (1.4826 MAD).
struct Band {
  double low = -1e300, high = 1e300, deviation = 0;
  bool holds(double v) const { return v >= low && v <= high; }
};

// The change from the inner to the outer side in the edge's polarity: positive when the outer side is
// the side the polarity expects (darker for Falling).
double step(double inner, double outer, EdgePolarity polarity) {
  if (polarity == EdgePolarity::Falling) return inner - outer;
  if (polarity == EdgePolarity::Rising) return outer - inner;
  return std::abs(outer - inner);
}

// The plateaus (normal_edges.h): for a falling edge nothing darker than the inner side over the plateau
// behind it and nothing darker than the outer side over the plateau beyond it, each within `tolerance`
// (brighter for a rising edge). An Either search checks the edge's own direction.
bool onPlateaus(const Profile& profile, int k, EdgePolarity polarity, double tolerance) {
  if (polarity == EdgePolarity::Either)
    polarity = profile.derivative[std::size_t(k)] < 0 ? EdgePolarity::Falling : EdgePolarity::Rising;
  const int outer = k + 2 * profile.side + 1;
  for (int j = k - profile.plateau(); j < k; ++j)  // NaN beyond the scan: not checked
    if (step(profile.inner(k), profile.at(j), polarity) > tolerance) return false;
  for (int j = outer + 1; j <= outer + profile.plateau(); ++j)
    if (step(profile.outer(k), profile.at(j), polarity) > tolerance) return false;
  return true;
}

// The tissue check: the inner side in the organ's band, the outer side `contrastMads` deviations beyond
// it, both sides on plateaus.
bool organOnInnerSide(const Profile& profile, int k, EdgePolarity polarity, const Band& organ,
                      const NormalEdgeOptions& o) {
  const double inner = profile.inner(k), outer = profile.outer(k);
  return organ.holds(inner) && step(inner, outer, polarity) >= o.contrastMads * organ.deviation &&
         onPlateaus(profile, k, polarity, o.plateauMads * organ.deviation);
}

// Index of the largest interior local maximum (above round-off) of the edge values that passes the tissue
// check against `organ`, or -1. With no band, any peak.
int strongestPeak(const Profile& profile, EdgePolarity polarity, const Band* organ = nullptr,
                  const NormalEdgeOptions* o = nullptr) {
  const std::vector<double>& d = profile.derivative;
  int best = -1;
  for (std::size_t k = 1; k + 1 < d.size(); ++k) {
    const double e = edgeValue(d[k], polarity);
    if (!(e > profile.noise && e >= edgeValue(d[k - 1], polarity) && e > edgeValue(d[k + 1], polarity))) continue;
    if (organ && !organOnInnerSide(profile, int(k), polarity, *organ, *o)) continue;
    if (best < 0 || e > edgeValue(d[std::size_t(best)], polarity)) best = int(k);
  }
  return best;
}

double median(std::vector<double> v) {
  auto middle = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), middle, v.end());
  return *middle;
}

// The organ's band from the blurred scan searchMm + sideMm inside every candidate (the inner end of its
// profile): median ± bandMads robust standard deviations (1.4826 MAD). Most of a roughly placed template's
// inside is the organ, so the median is the organ's intensity. (The inner sides of each profile's
// strongest edge were tried first: 59-77 % of suggestions on the boundary over four seeds, against 66-72 %.)
// An edge between two other tissues (where the template is off the organ) falls outside the band.
// The deviation is at least 0.5 % of the range of the profiles (the band 1 % either way with the default
// bandMads): a uniform organ (MAD 0, as in a phantom) still holds its own blurred values.
Band organBand(const std::vector<Profile>& profiles, const NormalEdgeOptions& o) {
  std::vector<double> inner;
  double lowest = 1e300, highest = -1e300;
  for (const Profile& p : profiles) {
    if (p.values.empty()) continue;
    inner.push_back(p.values.front());
    lowest = std::min(lowest, *std::min_element(p.values.begin(), p.values.end()));
    highest = std::max(highest, *std::max_element(p.values.begin(), p.values.end()));
  }
  if (inner.size() < 3) return {};
  const double m = median(inner);
  for (double& v : inner) v = std::abs(v - m);
  const double deviation = std::max(1.4826 * median(inner), 0.005 * (highest - lowest));
  return {m - o.bandMads * deviation, m + o.bandMads * deviation, deviation};
}

NormalEdge edgeOnProfile(const Profile& profile, const Eigen::Vector3d& p, const Eigen::Vector3d& n,
                         EdgePolarity polarity, const Band* organ, const NormalEdgeOptions& o) {
  NormalEdge edge;
  edge.position = p;
  const int k = profile.derivative.empty() ? -1 : strongestPeak(profile, polarity, organ, &o);
  if (k < 0) return edge;
  std::vector<double> magnitude;
  for (double d : profile.derivative) magnitude.push_back(std::abs(d));
  const double peak = std::abs(profile.derivative[std::size_t(k)]), typical = median(magnitude);
  edge.found = true;
  edge.offsetMm = -o.searchMm + k * o.stepMm;
  edge.position = p + n * edge.offsetMm;
  edge.strength = peak;
  const double contrast = (peak - typical) / (peak + typical),
               closeness = 1 - std::abs(edge.offsetMm) / (2 * o.searchMm);
  edge.confidence = std::clamp(contrast * closeness, 0.0, 1.0);
  return edge;
}

// Falling or Rising, whichever has the larger peak at more of the profiles (ties: Falling, the usual case
// of a soft-tissue organ against fat or air).
EdgePolarity majorityPolarity(const std::vector<Profile>& profiles) {
  long falling = 0, rising = 0;
  for (const Profile& p : profiles) {
    if (p.derivative.empty()) continue;
    const int f = strongestPeak(p, EdgePolarity::Falling), r = strongestPeak(p, EdgePolarity::Rising);
    if (f < 0 && r < 0) continue;
    const double fe = f < 0 ? 0 : -p.derivative[std::size_t(f)], re = r < 0 ? 0 : p.derivative[std::size_t(r)];
    (fe >= re ? falling : rising) += 1;
  }
  return rising > falling ? EdgePolarity::Rising : EdgePolarity::Falling;
}

}  // namespace

NormalEdges findNormalEdges(const Image& scan, const MatrixX3d& points, const MatrixX3d& normals,
                            const NormalEdgeOptions& options) {
  validate(points, normals, options);
  NormalEdges result;
  if (points.rows() == 0) return result;
  // Four sigmas hold the Gaussian's weight to 1e-4; beyond them the crop's edge cannot show in the blur.
  const double reach = options.searchMm + options.sideMm + options.plateauMm + options.stepMm + 4 * options.sigmaMm;
  const Grid<float> blurred = detail::gaussianSmoothMm(cropAround(scan, points, reach), options.sigmaMm);

  std::vector<Profile> profiles(std::size_t(points.rows()));
  std::vector<Eigen::Vector3d> units(std::size_t(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    units[std::size_t(i)] = normals.row(i).transpose().normalized();
    profiles[std::size_t(i)] = sampleProfile(blurred, points.row(i).transpose(), units[std::size_t(i)], options);
  }
  result.polarity = options.polarity == EdgePolarity::Auto ? majorityPolarity(profiles) : options.polarity;
  const Band organ = organBand(profiles, options);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    result.edges.push_back(edgeOnProfile(profiles[std::size_t(i)], points.row(i).transpose(), units[std::size_t(i)],
                                         result.polarity, options.checkTissue ? &organ : nullptr, options));
  return result;
}

}  // namespace vesalius::segmentation
