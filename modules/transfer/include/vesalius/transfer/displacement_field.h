// The volumetric displacement field of anatomy transfer (Dicko et al. 2013, §7): displacements given at scattered
// points (skin vertices, bone vertices) become the fixed cells of a grid over the reference body, and the
// Laplace interpolation (laplace_interpolation.h) fills the body's other cells, the three components in
// one 3-wide solve with the one set-up. Any reference point then moves by trilinear sampling of the field.
//
// Where Dicko et al. 2013 is silent:
//  - Domain: the cells inside the reference skin (a mask the caller computes, e.g. meshing's
//    meshInsideMask) plus the fixed cells the points give; the rest of the grid is Excluded. Domain cells
//    cut off from every fixed cell (a closed cavity) are Excluded too, as their values would be undefined.
//  - Beyond the domain the field is extended by `extrapolationLayers` rings of neighbour averages, so that
//    trilinear sampling of a point within a voxel or two outside the skin (a skin vertex, a muscle that
//    touches the skin) never mixes in cells that were not solved.
//  - The Jacobian determinant det(I + ∇u) is measured by central differences at every free or fixed cell
//    whose six neighbours are free or fixed; a positive minimum means the map is locally foldover-free
//    (Dicko et al.'s condition for organs not to intersect, §8).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/core/mesh.h"
#include "vesalius/transfer/laplace_interpolation.h"
#include "vesalius/transfer/point_constraints.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace vesalius::transfer {

struct DisplacementFieldOptions {
  LaplaceOptions laplace;
  SplatOptions splat;
  int extrapolationLayers = 3;
  // Up to `unfoldPasses` times: every fixed cell within `unfoldReach` cells of a folded cell (det ≤ 0,
  // measured as jacobianDeterminant does) is freed and the field solved again. Fixed values from two
  // surfaces a cell or two apart (the skin and a bone under it), or from a surface whose displacement
  // turns faster than a cell (the skin's shell where the registration squeezes it), can fold the cells
  // between; freeing them lets the field there be the interpolation's own.
  int unfoldPasses = 0;
  int unfoldReach = 2;
  double unfoldTolerance = 1e-4;  // the passes' solves stop here; the last is solved to laplace.tolerance
};

struct DisplacementField {
  std::array<Grid<double>, 3> components;  // displacement (mm, LPS) per cell
  std::vector<CellRole> roles;             // what each cell was in the solve
  std::array<LaplaceSolveInfo, 3> solves;
  int levels = 0;                          // multigrid levels used
  int unfoldPasses = 0;                    // passes that freed fixed cells (options.unfoldPasses)
  std::int64_t releasedCells = 0;          // fixed cells they freed

  const GridGeometry& geometry() const { return components[0].geometry; }
  // P: #P by 3 reference points → #P by 3 moved points P + u(P), u sampled trilinearly.
  MatrixX3d displace(const MatrixX3d& P) const;
  Eigen::Vector3d displacementAt(const Eigen::Vector3d& p) const;
};

// domain: inside mask of the reference body on the field's grid (nonzero inside). points: #P by 3 in the
// grid's world space, displacements: #P by 3. `initialGuess` (same grid), if given, starts the solves
// from a previous field. Throws BadInput if a point lies outside the grid or sizes disagree.
DisplacementField interpolateDisplacements(const Grid<std::uint8_t>& domain, const MatrixX3d& points,
                                           const MatrixX3d& displacements,
                                           const DisplacementFieldOptions& options = {},
                                           const DisplacementField* initialGuess = nullptr);

struct JacobianSummary {
  double minimum = 0;                 // smallest det(I + ∇u) over the measured cells
  Eigen::Vector3d whereMinimum = Eigen::Vector3d::Zero();  // world position of that cell
  std::int64_t measuredCells = 0;
  std::int64_t nonPositiveCells = 0;  // cells with det <= 0 (folds)
  // The same over the interior: free cells whose six neighbours are free too, i.e. where the field is
  // the interpolation's own and not the fixed values' (a fold there is the solver's, one at the fixed
  // shell comes from the given displacements).
  double interiorMinimum = 0;
  Eigen::Vector3d whereInteriorMinimum = Eigen::Vector3d::Zero();  // world position of that cell
  std::int64_t interiorCells = 0, interiorNonPositiveCells = 0;
};
JacobianSummary jacobianDeterminant(const DisplacementField& field);

}  // namespace vesalius::transfer
