// Laplace interpolation on a regular grid (Dicko et al. 2013, §7, Eqs. 1–2): values given on the fixed cells are
// extended into the free cells by solving
//   ∇²f(x) = 0 at free cells,   f(x) = f̄ at fixed cells,
// the "as linear as possible" interpolation the paper uses to carry skin (and later bone) displacements
// into the body, one displacement component per solve.
//
// Discretization: the 7-point Laplacian over voxel centres with the grid's spacing h = (hx, hy, hz) mm,
//   Σ_a (2 f_i − f_{i+e_a} − f_{i−e_a}) / h_a² = 0   at every free cell i,
// a finite-volume stencil: a neighbour that is Excluded or beyond the grid edge drops its term (zero
// flux, Neumann), a Fixed neighbour moves its value to the right-hand side. The system A f = b over the
// free cells is symmetric positive definite when every connected free region touches a fixed cell; the
// constructor checks this and throws BadInput otherwise (such a region's values would be undetermined).
// The grid's direction must be orthonormal (a rotation or reflection), so that the stencil is the world
// Laplacian.
//
// Solvers (all matrix-free on the grid):
//  - MultigridCG (default): CG preconditioned by one multigrid V-cycle (McAdams et al. 2010, the
//    "irregular boundaries" kind of multigrid Dicko et al. 2013 cites from Zhu et al. 2010). Robust to the thin,
//    irregular fixed shells of a skin.
//  - Multigrid: V-cycles used as a stationary iteration.
//  - ConjugateGradient: Jacobi-preconditioned CG, Dicko et al.'s baseline (they used Eigen's CG, whose default
//    preconditioner is the diagonal).
// Multigrid design (docs/methods/laplace-interpolation.md): cell-centred coarsening by 2×2×2 blocks,
// spacing doubled; a coarse cell is Fixed if any child is Fixed, else Free if any child is Free, else
// Excluded, so no coarse free region loses its fixed cells; the coarse operator is the rediscretized
// stencil, except that a Free cell couples to a Fixed neighbour with 1/θ, θ the distance to the finest
// Fixed cells inside it (ghost-fluid Dirichlet, Gibou et al. 2002); prolongation extrapolates the
// correction linearly to that boundary, then interpolates trilinearly, and restriction is its transpose / 8;
// red-black Gauss–Seidel, red then black before the coarse correction and black then red after, plus
// sweeps over a band of 2 cells along the Fixed cells (McAdams et al.), so the V-cycle is symmetric (a
// valid CG preconditioner); the coarsest level is solved by Jacobi-CG to 1e-12.
// Measured per iteration on 64³ (tests): MG-PCG reduces the residual 13–24×, V-cycles alone 4–10×.
// Several fields at once: the three components of a displacement share the matrix, so solve(fields)
// carries them as one 3-wide field per cell (one pass over roles and coefficients serves x, y and z)
// with a CG (α, β, stopping) per component; each component comes out bitwise equal to solve(field) on it.
// Speed (issue 7): kernels visit each grid row only between its first and last Free cell, so Excluded
// space around a body costs no memory traffic; a red-black sweep is one pass over memory; restriction
// is separable. Dicko et al.'s 309×839×142 grid, one field: 31 s wall (15.7 s CPU) on the shared 2-core machine,
// 13× faster than Jacobi-CG in the same run (bench_transfer).
// Threads: smoothing, residuals and transfers run in parallel with TBB; every cell's update reads only
// cells of the other colour or of another level, and dot products are summed per grid plane and then
// over the planes in order, so results are bitwise identical for any number of threads.
#pragma once

#include "vesalius/core/grid.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace vesalius::transfer {

enum class CellRole : std::uint8_t {
  Free,      // unknown: the discrete Laplacian is zero here
  Fixed,     // Dirichlet: the value is given (Dicko et al. 2013, §7 Eq. 2)
  Excluded,  // not part of the domain (e.g. outside the body): no unknown, no flux to its neighbours
};

enum class LaplaceSolver { MultigridCG, Multigrid, ConjugateGradient };

struct LaplaceOptions {
  LaplaceSolver solver = LaplaceSolver::MultigridCG;
  // Stop when ‖b − A f‖₂ ≤ tolerance · ‖b‖₂ (b: the fixed values' contribution to the free cells).
  double tolerance = 1e-8;
  int maxCycles = 200;               // iteration limit of Multigrid and MultigridCG
  int maxCgIterations = 1000000;     // iteration limit of ConjugateGradient
  int smoothingSweeps = 3;           // red-black Gauss–Seidel sweeps before and after each coarse correction
  int boundarySweeps = 2;            // extra sweeps over the Free cells within 2 cells of a Fixed one, each side
  std::int64_t coarsestCells = 4096; // stop coarsening at this many cells, or when an axis gets below 4 cells
};

struct LaplaceSolveInfo {
  int iterations = 0;                 // V-cycles (Multigrid) or CG iterations
  double relativeResidual = 0;        // the true ‖b − A f‖ / ‖b‖ on return
  // Relative residual at the start and after each iteration (for the CG solvers, that of CG's recurrence).
  std::vector<double> residualHistory;
};

// Set up once for a grid and its cell roles, then solve for any number of fields (x, y, z displacement
// components, other per-cell quantities) with the same fixed cells.
class LaplaceInterpolator {
 public:
  // roles: geometry.voxelCount() entries, in the grid's order (i fastest). Throws BadInput on a size
  // mismatch, an invalid or non-orthonormal geometry, or a free region that touches no fixed cell.
  LaplaceInterpolator(const GridGeometry& geometry, const std::vector<CellRole>& roles,
                      const LaplaceOptions& options = {});
  ~LaplaceInterpolator();
  LaplaceInterpolator(LaplaceInterpolator&&) noexcept;
  LaplaceInterpolator& operator=(LaplaceInterpolator&&) noexcept;

  // field: same size as the grid. In: values at Fixed cells (the boundary condition) and the initial
  // guess at Free cells (0 is fine; a previous solution speeds up a similar solve). Out: the harmonic
  // values at Free cells; Fixed and Excluded cells are left as they were. Throws BadInput on a size
  // mismatch or a non-finite value at a Fixed or Free cell, NumericalFailure if the solver reaches its
  // iteration limit above the tolerance.
  LaplaceSolveInfo solve(Grid<double>& field);
  // The same for three fields (e.g. a displacement's x, y, z components) in one pass per sweep: each
  // field and its info are bitwise those of solve(field) on it alone. Measured: 25 % less CPU than three
  // single solves on 2 M free cells, about the same on 18 M (docs/methods/laplace-interpolation.md);
  // needs 3× the memory of solve(field) while solving.
  std::array<LaplaceSolveInfo, 3> solve(std::array<Grid<double>, 3>& fields);

  std::int64_t freeCount() const;
  int levelCount() const;  // 1 for ConjugateGradient; the multigrid hierarchy's depth otherwise
  const LaplaceOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vesalius::transfer
