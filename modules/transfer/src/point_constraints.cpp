#include "vesalius/transfer/point_constraints.h"

#include "vesalius/core/error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace vesalius::transfer {
namespace {

struct Contribution {
  std::int64_t voxel;
  Eigen::Index point;
  double weight;
};

// The continuous index of point p, checked to lie inside the grid's voxel-centre box.
Eigen::Vector3d indexInside(const GridGeometry& g, const MatrixX3d& points, Eigen::Index p) {
  const Eigen::Vector3d x = points.row(p).transpose();
  if (!x.allFinite()) throw BadInput("", "Laplace constraints: point " + std::to_string(p) + " is not finite");
  const Eigen::Vector3d u = g.worldToIndex(x);
  constexpr double kSlack = 1e-9;  // round-off of worldToIndex at the grid's faces
  for (int a = 0; a < 3; ++a)
    if (!(u[a] >= -kSlack && u[a] <= g.size[a] - 1 + kSlack))
      throw BadInput("", "Laplace constraints: point " + std::to_string(p) + " lies outside the grid");
  return u.cwiseMax(Eigen::Vector3d::Zero()).cwiseMin((g.size.array() - 1).cast<double>().matrix());
}

void addContributions(const GridGeometry& g, const Eigen::Vector3d& u, Eigen::Index p, SplatMethod method,
                      std::vector<Contribution>& out) {
  if (method == SplatMethod::Nearest) {
    const Eigen::Vector3i v = u.array().round().cast<int>();
    out.push_back({g.linearIndex(v.x(), v.y(), v.z()), p, 1.0});
    return;
  }
  const Eigen::Vector3i base = u.array().floor().cast<int>();
  const Eigen::Vector3d t = u - base.cast<double>();
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3i v = base + Eigen::Vector3i(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    double w = 1;
    for (int a = 0; a < 3; ++a) w *= (v[a] == base[a]) ? 1 - t[a] : t[a];
    if (w > 0) out.push_back({g.linearIndex(v.x(), v.y(), v.z()), p, w});  // w > 0 implies v is in the grid
  }
}

}  // namespace

VoxelConstraints splatPointValues(const GridGeometry& geometry, const MatrixX3d& points,
                                  const Eigen::MatrixXd& values, const SplatOptions& options) {
  geometry.validate("Laplace constraints grid");
  if (points.rows() != values.rows())
    throw BadInput("", "Laplace constraints: " + std::to_string(points.rows()) + " points but " +
                           std::to_string(values.rows()) + " rows of values");
  if (!values.allFinite()) throw BadInput("", "Laplace constraints: a point value is not finite");
  std::vector<Contribution> contributions;
  contributions.reserve(points.rows() * (options.method == SplatMethod::Nearest ? 1 : 8));
  for (Eigen::Index p = 0; p < points.rows(); ++p)
    addContributions(geometry, indexInside(geometry, points, p), p, options.method, contributions);
  // Sorting by voxel (then point, for a fixed summation order) groups each voxel's contributions.
  std::sort(contributions.begin(), contributions.end(), [](const Contribution& a, const Contribution& b) {
    return a.voxel != b.voxel ? a.voxel < b.voxel : a.point < b.point;
  });
  VoxelConstraints result;
  result.values.resize(Eigen::Index(contributions.size()), values.cols());
  for (std::size_t begin = 0; begin < contributions.size();) {
    std::size_t end = begin;
    double weight = 0;
    Eigen::RowVectorXd sum = Eigen::RowVectorXd::Zero(values.cols());
    for (; end < contributions.size() && contributions[end].voxel == contributions[begin].voxel; ++end) {
      weight += contributions[end].weight;
      sum += contributions[end].weight * values.row(contributions[end].point);
    }
    result.values.row(Eigen::Index(result.voxels.size())) = sum / weight;
    result.voxels.push_back(contributions[begin].voxel);
    begin = end;
  }
  result.values.conservativeResize(Eigen::Index(result.voxels.size()), values.cols());
  return result;
}

void fixConstrainedVoxels(const VoxelConstraints& constraints, std::vector<CellRole>& roles) {
  for (std::int64_t v : constraints.voxels) {
    if (v < 0 || v >= std::int64_t(roles.size()))
      throw BadInput("", "Laplace constraints: a constrained voxel lies outside the role grid");
    roles[v] = CellRole::Fixed;
  }
}

void writeConstraintValues(const VoxelConstraints& constraints, int column, Grid<double>& field) {
  if (column < 0 || column >= constraints.values.cols())
    throw UsageError("Laplace constraints: no value column " + std::to_string(column));
  for (std::size_t c = 0; c < constraints.voxels.size(); ++c) {
    const std::int64_t v = constraints.voxels[c];
    if (v < 0 || v >= std::int64_t(field.values.size()))
      throw BadInput("", "Laplace constraints: a constrained voxel lies outside the field's grid");
    field.values[v] = constraints.values(Eigen::Index(c), column);
  }
}

}  // namespace vesalius::transfer
