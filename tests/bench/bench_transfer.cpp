// Benchmark of the Laplace interpolation of seed 000 §7: multigrid-preconditioned CG and plain V-cycles
// against the seed's baseline, Jacobi-preconditioned CG (Eigen's CG with its default preconditioner), on
// the same grid, boundary values and relative residual 1e-8, in the same run.
// The domain is body-like: the ellipsoid inscribed in the grid (2 voxels of margin) is Free, a shell
// 1.5 voxels thick around it is Fixed with a smooth displacement-like field, the outside is Excluded, as
// for a skin inside its bounding grid. Spacing 1 × 1 × 1.5 mm, anisotropic like a CT.
// Usage: bench_transfer [grid ...], each grid 64, 128 or paper (the seed's 309×839×142); default 64 128.
#include "bench_support.h"

#include "vesalius/transfer/laplace_interpolation.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <memory>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

Eigen::Vector3i gSize;  // the grid of the current child run (inChild takes a plain function)

std::vector<CellRole> ellipsoidRoles(const GridGeometry& g) {
  const Eigen::Vector3d centre = (g.size.cast<double>().array() - 1).matrix() / 2;
  const Eigen::Vector3d semi = centre.array() - 2;  // in voxels
  std::vector<CellRole> roles(g.voxelCount(), CellRole::Excluded);
  const double shell = 1.5 / semi.minCoeff();  // about 1.5 voxels, in the normalized radius
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const double rho = ((Eigen::Vector3d(i, j, k) - centre).array() / semi.array()).matrix().norm();
        if (rho < 1) roles[g.linearIndex(i, j, k)] = CellRole::Free;
        else if (rho < 1 + shell) roles[g.linearIndex(i, j, k)] = CellRole::Fixed;
      }
  return roles;
}

Grid<double> boundaryValues(const GridGeometry& g) {
  Grid<double> field(g, 0.0);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const Eigen::Vector3d x = g.indexToWorld(Eigen::Vector3d(i, j, k));
        field.at(i, j, k) = 5 * std::sin(x.x() / 17) * std::cos(x.y() / 23) + 0.01 * x.x() * x.z();
      }
  return field;
}

struct Run {
  double setup = 0, solve = 0;
  LaplaceSolveInfo info;
};

Run run(const GridGeometry& g, const std::vector<CellRole>& roles, LaplaceSolver solver, int* levels = nullptr) {
  LaplaceOptions options;
  options.solver = solver;
  options.tolerance = 1e-8;
  Run r;
  std::unique_ptr<LaplaceInterpolator> interpolator;
  r.setup = bench::seconds([&] { interpolator = std::make_unique<LaplaceInterpolator>(g, roles, options); });
  if (levels) *levels = interpolator->levelCount();
  Grid<double> field = boundaryValues(g);
  r.solve = bench::seconds([&] { r.info = interpolator->solve(field); });
  return r;
}

// Geometric mean of the residual's reduction per iteration.
double meanFactor(const LaplaceSolveInfo& info) {
  return std::pow(info.residualHistory.back() / info.residualHistory.front(), 1.0 / info.iterations);
}

void oneGrid() {
  GridGeometry g;
  g.size = gSize;
  g.spacing = Eigen::Vector3d(1, 1, 1.5);
  const std::vector<CellRole> roles = ellipsoidRoles(g);
  std::int64_t freeCells = 0;
  for (CellRole r : roles) freeCells += r == CellRole::Free;
  int levels = 0;
  const Run mgcg = run(g, roles, LaplaceSolver::MultigridCG, &levels);
  const Run mg = run(g, roles, LaplaceSolver::Multigrid);
  const Run cg = run(g, roles, LaplaceSolver::ConjugateGradient);
  std::printf("| %d×%d×%d | %.2f M | %d | %.2f s + %.2f s, %d it (×%.3f) | %.2f s, %d cycles (×%.3f) | "
              "%.2f s, %d it | %.1f× | %.1f× |",
              gSize.x(), gSize.y(), gSize.z(), freeCells / 1e6, levels, mgcg.setup, mgcg.solve, mgcg.info.iterations,
              meanFactor(mgcg.info), mg.setup + mg.solve, mg.info.iterations, meanFactor(mg.info), cg.solve,
              cg.info.iterations, cg.solve / (mgcg.setup + mgcg.solve), cg.solve / (mg.setup + mg.solve));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> grids(argv + 1, argv + argc);
  if (grids.empty()) grids = {"64", "128"};
  std::printf("| grid | free cells | levels | MG-PCG: setup + solve, iterations (mean residual factor) | "
              "V-cycles: setup + solve, cycles (factor) | Jacobi-CG: solve, iterations | CG / MG-PCG | "
              "CG / V-cycles | peak memory |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& grid : grids) {
    if (grid == "paper") gSize = Eigen::Vector3i(309, 839, 142);
    else if (grid == "64" || grid == "128") gSize = Eigen::Vector3i::Constant(std::stoi(grid));
    else {
      std::fprintf(stderr, "bench_transfer: unknown grid %s (64, 128 or paper)\n", grid.c_str());
      return 2;
    }
    bench::inChild(oneGrid);
  }
  return 0;
}
