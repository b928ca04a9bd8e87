#include "warped_patient.h"

#include "vesalius/core/grid_sampling.h"

#include <Eigen/LU>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace vesalius::test {

namespace {

// 1 within `plateau`, 0 beyond `support`, C2 between.
double radialWeight(double r, double plateau, double support) {
  if (r <= plateau) return 1.0;
  if (r >= support) return 0.0;
  const double u = (r - plateau) / (support - plateau);
  return 1.0 - u * u * u * (10.0 + u * (-15.0 + 6.0 * u));
}

}  // namespace

WarpField::WarpField(const LabelMap& labels, const std::vector<OrganWarp>& warps, int steps) : steps_(steps) {
  const GridGeometry& g = labels.labels.geometry;
  for (const OrganWarp& w : warps) {
    const LabelEntry* entry = labels.table.find(w.organ);
    if (!entry) throw std::runtime_error("warpPatient: no label '" + w.organ + "' in the table");
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < g.size.z(); ++k)
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i)
          if (labels.labels.at(i, j, k) == entry->id) points.push_back(g.indexToWorld(Eigen::Vector3d(i, j, k)));
    if (points.empty()) throw std::runtime_error("warpPatient: label '" + w.organ + "' has no voxels");
    Part p;
    p.centre.setZero();
    for (const Eigen::Vector3d& x : points) p.centre += x;
    p.centre /= double(points.size());
    double sum2 = 0, rmax = 0;
    for (const Eigen::Vector3d& x : points) {
      sum2 += (x - p.centre).squaredNorm();
      rmax = std::max(rmax, (x - p.centre).norm());
    }
    p.plateau = std::sqrt(sum2 / double(points.size()));
    p.support = rmax + p.plateau;
    for (int a = 0; a < 3; ++a) {
      if (!(w.scale[a] > 0)) throw std::runtime_error("warpPatient: scale must be positive");
      p.a[a] = std::log(w.scale[a]);
      // Where w = 1 the flow of A(x - c) + b moves c by (e^A - I) A⁻¹ b: b is chosen to make that t.
      p.b[a] = std::abs(p.a[a]) < 1e-12 ? w.shiftMm[a] : w.shiftMm[a] * p.a[a] / (w.scale[a] - 1.0);
    }
    parts_.push_back(p);
  }
}

Eigen::Vector3d WarpField::velocity(const Eigen::Vector3d& x) const {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  double weights = 0;
  for (const Part& p : parts_) {
    const Eigen::Vector3d d = x - p.centre;
    const double w = radialWeight(d.norm(), p.plateau, p.support);
    if (w > 0) v += w * (p.a.cwiseProduct(d) + p.b), weights += w;
  }
  // Where the weights sum past 1 (organs close together) the organs' velocities are averaged, so that
  // their scales do not compound. max(1, ·) is Lipschitz, so the flow stays a diffeomorphism.
  return weights > 1 ? Eigen::Vector3d(v / weights) : v;
}

// A point outside every support has zero velocity and so never moves.
bool WarpField::atRest(const Eigen::Vector3d& x) const {
  for (const Part& p : parts_)
    if ((x - p.centre).norm() < p.support) return false;
  return true;
}

Eigen::Vector3d WarpField::flow(Eigen::Vector3d x, double sign) const {
  if (atRest(x)) return x;
  const double h = sign / double(steps_);
  for (int s = 0; s < steps_; ++s) {
    const Eigen::Vector3d k1 = velocity(x), k2 = velocity(x + 0.5 * h * k1), k3 = velocity(x + 0.5 * h * k2),
                          k4 = velocity(x + h * k3);
    x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return x;
}

Eigen::Vector3d WarpField::forward(const Eigen::Vector3d& x) const { return flow(x, 1.0); }
Eigen::Vector3d WarpField::backward(const Eigen::Vector3d& y) const { return flow(y, -1.0); }

WarpedPatient warpPatient(const Image& ct, const LabelMap& labels, const std::vector<OrganWarp>& warps) {
  const GridGeometry& g = labels.labels.geometry;
  if (ct.geometry.size != g.size) throw std::runtime_error("warpPatient: the CT and its labels differ in size");
  const WarpField field(labels, warps);

  // φ⁻¹ at every voxel centre, in continuous index space of the (shared) grid.
  const std::int64_t n = g.voxelCount();
  std::vector<Eigen::Vector3d> source(std::size_t(n), Eigen::Vector3d::Zero());
  tbb::parallel_for(0, g.size.z(), [&](int k) {
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        source[std::size_t(g.linearIndex(i, j, k))] =
            g.worldToIndex(field.backward(g.indexToWorld(Eigen::Vector3d(i, j, k))));
  });

  WarpedPatient out;
  out.ct = ct;
  out.labels = labels;
  tbb::parallel_for(std::int64_t(0), n, [&](std::int64_t v) {
    const Eigen::Vector3d& s = source[std::size_t(v)];
    out.ct.values[std::size_t(v)] = float(sampleTrilinear(ct, s));
    const Eigen::Vector3i r(int(std::lround(s.x())), int(std::lround(s.y())), int(std::lround(s.z())));
    out.labels.labels.values[std::size_t(v)] =
        g.contains(r.x(), r.y(), r.z()) ? labels.labels.at(r.x(), r.y(), r.z()) : Label(0);
  });

  // det ∂φ⁻¹/∂y by central differences (one-sided at the grid's faces) in index space, where the grid's
  // own Jacobian cancels; det ∂φ/∂x is its reciprocal.
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const Eigen::Vector3i c(i, j, k);
        Eigen::Matrix3d J;
        for (int a = 0; a < 3; ++a) {
          Eigen::Vector3i m = c, p = c;
          if (c[a] > 0) m[a] -= 1;
          if (c[a] < g.size[a] - 1) p[a] += 1;
          if (m[a] == p[a]) {
            J.col(a) = Eigen::Vector3d::Unit(a);
            continue;
          }
          J.col(a) = (source[std::size_t(g.linearIndex(p.x(), p.y(), p.z()))] -
                      source[std::size_t(g.linearIndex(m.x(), m.y(), m.z()))]) /
                     double(p[a] - m[a]);
        }
        const double det = J.determinant();
        const double forward = det > 0 ? 1.0 / det : -std::numeric_limits<double>::infinity();
        lo = std::min(lo, forward);
        hi = std::max(hi, forward);
      }
  out.minJacobian = lo;
  out.maxJacobian = hi;
  return out;
}

}  // namespace vesalius::test
