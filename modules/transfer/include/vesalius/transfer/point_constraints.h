// Dirichlet values from scattered points: how the skin vertices' displacements (and later the bones')
// become the fixed cells f̄ of the Laplace interpolation (Dicko et al. 2013, §7, Eq. 2).
//
// Dicko et al. 2013 fixes "the boundary" of its grid without saying how mesh vertices map to voxels. Two ways:
//  - Trilinear (default): each point spreads its value over the 8 voxel centres around it with its
//    trilinear weights; a voxel takes the weighted mean of the points that reach it and becomes Fixed.
//    Every point counts (none is lost when several share a voxel), a voxel's value is a local average of
//    the surface's values within one voxel, and a surface sampled at least once per voxel yields a fixed
//    shell two voxels thick with no gaps for the interior to leak through.
//  - Nearest: each point fixes only the voxel centre nearest to it (mean of the points sharing it): a
//    thinner shell, exact where a point sits on a voxel centre, but it has holes where the surface is
//    sampled more sparsely than the grid.
// Either way a voxel's value is an average of nearby point values, so a smooth field is reproduced to
// O(h · |∇f|) at the shell, h the spacing.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"
#include "vesalius/transfer/laplace_interpolation.h"

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace vesalius::transfer {

enum class SplatMethod { Trilinear, Nearest };

struct SplatOptions {
  SplatMethod method = SplatMethod::Trilinear;
};

struct VoxelConstraints {
  std::vector<std::int64_t> voxels;  // linear grid indices (i fastest), ascending, each once
  Eigen::MatrixXd values;            // voxels.size() by the number of value columns
};

// points: #P by 3 world positions (mm, LPS); values: #P by m (e.g. the three displacement components).
// Throws BadInput if the row counts differ, a point or value is not finite, or a point lies outside the
// grid (the grid must cover every constrained point).
VoxelConstraints splatPointValues(const GridGeometry& geometry, const MatrixX3d& points,
                                  const Eigen::MatrixXd& values, const SplatOptions& options = {});

// Marks the constrained voxels Fixed (roles: geometry.voxelCount() entries).
void fixConstrainedVoxels(const VoxelConstraints& constraints, std::vector<CellRole>& roles);

// Writes column `column` of the constraint values into field at the constrained voxels.
void writeConstraintValues(const VoxelConstraints& constraints, int column, Grid<double>& field);

}  // namespace vesalius::transfer
