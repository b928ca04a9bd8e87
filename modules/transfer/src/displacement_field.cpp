// Displacement fields by Laplace interpolation (displacement_field.h).
#include "vesalius/transfer/displacement_field.h"

#include "vesalius/core/error.h"
#include "vesalius/core/grid_sampling.h"

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

#include <limits>
#include <string>

namespace vesalius::transfer {

namespace {

constexpr int kNeighbours[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

template <class Visit>
void forEachNeighbour(const GridGeometry& g, std::int64_t cell, Visit visit) {
  const int i = int(cell % g.size.x()), j = int(cell / g.size.x() % g.size.y()),
            k = int(cell / (std::int64_t(g.size.x()) * g.size.y()));
  for (const auto& d : kNeighbours)
    if (g.contains(i + d[0], j + d[1], k + d[2])) visit(g.linearIndex(i + d[0], j + d[1], k + d[2]));
}

// Free cells that no path of free cells joins to a fixed cell become Excluded.
void excludeUnreachedCells(const GridGeometry& g, std::vector<CellRole>& roles) {
  std::vector<std::uint8_t> reached(roles.size(), 0);
  std::vector<std::int64_t> stack;
  for (std::int64_t c = 0; c < std::int64_t(roles.size()); ++c)
    if (roles[c] == CellRole::Fixed) stack.push_back(c), reached[c] = 1;
  while (!stack.empty()) {
    const std::int64_t c = stack.back();
    stack.pop_back();
    forEachNeighbour(g, c, [&](std::int64_t n) {
      if (!reached[n] && roles[n] == CellRole::Free) reached[n] = 1, stack.push_back(n);
    });
  }
  for (std::int64_t c = 0; c < std::int64_t(roles.size()); ++c)
    if (roles[c] == CellRole::Free && !reached[c]) roles[c] = CellRole::Excluded;
}

// Rings of neighbour averages into the Excluded cells next to solved ones (see the header).
void extrapolate(const std::vector<CellRole>& roles, int layers, std::array<Grid<double>, 3>& u) {
  const GridGeometry& g = u[0].geometry;
  std::vector<std::uint8_t> known(roles.size());
  for (std::size_t c = 0; c < roles.size(); ++c) known[c] = roles[c] != CellRole::Excluded;
  for (int layer = 0; layer < layers; ++layer) {
    std::vector<std::int64_t> ring;
    for (std::int64_t c = 0; c < std::int64_t(roles.size()); ++c) {
      if (known[c]) continue;
      bool touches = false;
      forEachNeighbour(g, c, [&](std::int64_t n) { touches = touches || known[n]; });
      if (touches) ring.push_back(c);
    }
    for (const std::int64_t c : ring) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      int count = 0;
      forEachNeighbour(g, c, [&](std::int64_t n) {
        if (!known[n]) return;
        for (int a = 0; a < 3; ++a) sum[a] += u[a].values[n];
        ++count;
      });
      for (int a = 0; a < 3; ++a) u[a].values[c] = sum[a] / count;
    }
    for (const std::int64_t c : ring) known[c] = 1;
  }
}

// d(index)/d(world): the inverse of direction · diag(spacing).
Eigen::Matrix3d indexPerWorld(const GridGeometry& g) { return (g.direction * g.spacing.asDiagonal()).inverse(); }

// Whether det(I + ∇u) is measured at cell (i, j, k): a free or fixed cell off the grid's border whose six
// neighbours are free or fixed.
bool measured(const DisplacementField& field, int i, int j, int k) {
  const GridGeometry& g = field.geometry();
  if (i < 1 || j < 1 || k < 1 || i + 1 >= g.size.x() || j + 1 >= g.size.y() || k + 1 >= g.size.z()) return false;
  const std::int64_t c = g.linearIndex(i, j, k);
  if (field.roles[c] == CellRole::Excluded) return false;
  bool inside = true;
  forEachNeighbour(g, c, [&](std::int64_t n) { inside = inside && field.roles[n] != CellRole::Excluded; });
  return inside;
}

// det(I + ∇u) at cell (i, j, k), ∇u by central differences.
double determinantAt(const DisplacementField& field, const Eigen::Matrix3d& perWorld, int i, int j, int k) {
  Eigen::Matrix3d gradient;  // ∂u_a / ∂index_b
  for (int a = 0; a < 3; ++a) {
    const Grid<double>& u = field.components[a];
    gradient(a, 0) = 0.5 * (u.at(i + 1, j, k) - u.at(i - 1, j, k));
    gradient(a, 1) = 0.5 * (u.at(i, j + 1, k) - u.at(i, j - 1, k));
    gradient(a, 2) = 0.5 * (u.at(i, j, k + 1) - u.at(i, j, k - 1));
  }
  return (Eigen::Matrix3d::Identity() + gradient * perWorld).determinant();
}

// Every fixed cell within `reach` cells (a cube) of a folded cell (det ≤ 0) becomes free; how many.
std::int64_t releaseFoldedFixedCells(DisplacementField& field, int reach) {
  const GridGeometry& g = field.geometry();
  const Eigen::Matrix3d perWorld = indexPerWorld(g);
  std::vector<std::int64_t> release;
  for (int k = 1; k + 1 < g.size.z(); ++k)
    for (int j = 1; j + 1 < g.size.y(); ++j)
      for (int i = 1; i + 1 < g.size.x(); ++i) {
        if (!measured(field, i, j, k) || determinantAt(field, perWorld, i, j, k) > 0) continue;
        for (int dk = -reach; dk <= reach; ++dk)
          for (int dj = -reach; dj <= reach; ++dj)
            for (int di = -reach; di <= reach; ++di)
              if (g.contains(i + di, j + dj, k + dk)) release.push_back(g.linearIndex(i + di, j + dj, k + dk));
      }
  std::int64_t released = 0;
  for (const std::int64_t c : release)
    if (field.roles[c] == CellRole::Fixed) field.roles[c] = CellRole::Free, ++released;
  return released;
}

}  // namespace

Eigen::Vector3d DisplacementField::displacementAt(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d index = geometry().worldToIndex(p);
  return {sampleTrilinear(components[0], index), sampleTrilinear(components[1], index),
          sampleTrilinear(components[2], index)};
}

MatrixX3d DisplacementField::displace(const MatrixX3d& P) const {
  MatrixX3d moved(P.rows(), 3);
  tbb::parallel_for(Eigen::Index(0), P.rows(), [&](Eigen::Index r) {
    const Eigen::Vector3d p = P.row(r).transpose();
    moved.row(r) = (p + displacementAt(p)).transpose();
  });
  return moved;
}

DisplacementField interpolateDisplacements(const Grid<std::uint8_t>& domain, const MatrixX3d& points,
                                           const MatrixX3d& displacements,
                                           const DisplacementFieldOptions& options,
                                           const DisplacementField* initialGuess) {
  const GridGeometry& g = domain.geometry;
  if (std::int64_t(domain.values.size()) != g.voxelCount())
    throw BadInput("", "displacement field: the domain mask does not match its grid");
  if (initialGuess && initialGuess->geometry().size != g.size)
    throw BadInput("", "displacement field: the initial guess lies on another grid");
  const VoxelConstraints constraints = splatPointValues(g, points, displacements, options.splat);

  DisplacementField field;
  field.roles.assign(g.voxelCount(), CellRole::Excluded);
  for (std::int64_t c = 0; c < g.voxelCount(); ++c)
    if (domain.values[c]) field.roles[c] = CellRole::Free;
  fixConstrainedVoxels(constraints, field.roles);
  excludeUnreachedCells(g, field.roles);

  for (int a = 0; a < 3; ++a) {
    field.components[a] = initialGuess ? initialGuess->components[a] : Grid<double>(g, 0.0);
    for (std::int64_t c = 0; c < g.voxelCount(); ++c)
      if (field.roles[c] != CellRole::Free) field.components[a].values[c] = 0.0;
    writeConstraintValues(constraints, a, field.components[a]);
  }
  const auto solve = [&](const LaplaceOptions& laplaceOptions) {
    LaplaceInterpolator laplace(g, field.roles, laplaceOptions);
    field.levels = laplace.levelCount();
    field.solves = laplace.solve(field.components);
  };
  solve(options.laplace);
  // The passes' solves start from the last and need only find where it still folds; the last is solved
  // to the full tolerance, and looked at again.
  LaplaceOptions rough = options.laplace;
  rough.tolerance = std::max(options.laplace.tolerance, options.unfoldTolerance);
  bool roughlySolved = false;
  for (int pass = 0; pass < options.unfoldPasses; ++pass) {
    const std::int64_t released = releaseFoldedFixedCells(field, options.unfoldReach);
    if (released == 0 && !roughlySolved) break;
    excludeUnreachedCells(g, field.roles);  // a pocket whose every fixed cell was freed has no values
    field.releasedCells += released;
    field.unfoldPasses += released > 0;
    roughlySolved = released > 0;
    solve(roughlySolved ? rough : options.laplace);
  }
  if (roughlySolved) solve(options.laplace);
  extrapolate(field.roles, options.extrapolationLayers, field.components);
  return field;
}

JacobianSummary jacobianDeterminant(const DisplacementField& field) {
  const GridGeometry& g = field.geometry();
  const Eigen::Matrix3d perWorld = indexPerWorld(g);
  JacobianSummary summary;
  summary.minimum = summary.interiorMinimum = std::numeric_limits<double>::infinity();
  std::int64_t minimumCell = -1, interiorMinimumCell = -1;
  for (int k = 1; k + 1 < g.size.z(); ++k)
    for (int j = 1; j + 1 < g.size.y(); ++j)
      for (int i = 1; i + 1 < g.size.x(); ++i) {
        if (!measured(field, i, j, k)) continue;
        const std::int64_t c = g.linearIndex(i, j, k);
        bool interior = field.roles[c] == CellRole::Free;
        forEachNeighbour(g, c, [&](std::int64_t n) { interior = interior && field.roles[n] == CellRole::Free; });
        const double det = determinantAt(field, perWorld, i, j, k);
        ++summary.measuredCells;
        if (det <= 0) ++summary.nonPositiveCells;
        if (det < summary.minimum) summary.minimum = det, minimumCell = c;
        if (!interior) continue;
        ++summary.interiorCells;
        if (det <= 0) ++summary.interiorNonPositiveCells;
        if (det < summary.interiorMinimum) summary.interiorMinimum = det, interiorMinimumCell = c;
      }
  const auto centre = [&g](std::int64_t c) {
    return g.indexToWorld(Eigen::Vector3d(double(c % g.size.x()), double(c / g.size.x() % g.size.y()),
                                          double(c / (std::int64_t(g.size.x()) * g.size.y()))));
  };
  if (minimumCell >= 0) summary.whereMinimum = centre(minimumCell);
  else summary.minimum = 0;
  if (interiorMinimumCell >= 0) summary.whereInteriorMinimum = centre(interiorMinimumCell);
  else summary.interiorMinimum = 0;
  return summary;
}

}  // namespace vesalius::transfer
