// Benchmark of the Laplace interpolation of Dicko et al. 2013, §7: multigrid-preconditioned CG (one field, and the
// three components of a displacement in one 3-wide solve) and plain V-cycles against Dicko et al.'s baseline,
// Jacobi-preconditioned CG (Eigen's CG with its default preconditioner), on the same grid, boundary values
// and relative residual 1e-8, in the same run.
// The domain is body-like: the ellipsoid inscribed in the grid (2 voxels of margin) is Free, a shell
// 1.5 voxels thick around it is Fixed with smooth displacement-like fields, the outside is Excluded, as
// for a skin inside its bounding grid. Spacing 1 × 1 × 1.5 mm, anisotropic like a CT.
// Times are wall clock; CPU time (both threads) is given too because the machine is shared, with the
// 1-minute load average before and after each grid's row. Jacobi-CG is run for the first field only:
// "3 CG" is three times that solve (each component's own CG would take about as many iterations).
// Usage: bench_transfer [grid ...], each grid 64, 128, half (155×420×71) or paper (Dicko et al.'s
// 309×839×142); default 64 128.
#include "bench_support.h"

#include "vesalius/transfer/laplace_interpolation.h"

#include <sys/resource.h>

#include <array>
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

// Component c of a smooth displacement-like field (mm).
Grid<double> boundaryValues(const GridGeometry& g, int c) {
  Grid<double> field(g, 0.0);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const Eigen::Vector3d x = g.indexToWorld(Eigen::Vector3d(i, j, k));
        field.at(i, j, k) = c == 0   ? 5 * std::sin(x.x() / 17) * std::cos(x.y() / 23) + 0.01 * x.x() * x.z()
                            : c == 1 ? 4 * std::cos(x.z() / 19) - 0.02 * x.y() + 0.005 * x.x() * x.y()
                                     : 3 * std::sin((x.y() + x.z()) / 29) + 0.03 * x.z();
      }
  return field;
}

double cpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

struct Run {
  double setup = 0, solve = 0, cpu = 0;  // wall s, wall s, CPU s of both
  std::array<LaplaceSolveInfo, 3> info;
  int levels = 0;
};

Run run(const GridGeometry& g, const std::vector<CellRole>& roles, LaplaceSolver solver, int fields) {
  LaplaceOptions options;
  options.solver = solver;
  options.tolerance = 1e-8;
  std::array<Grid<double>, 3> values;
  for (int c = 0; c < fields; ++c) values[c] = boundaryValues(g, c);
  Run r;
  const double cpuStart = cpuSeconds();
  std::unique_ptr<LaplaceInterpolator> interpolator;
  r.setup = bench::seconds([&] { interpolator = std::make_unique<LaplaceInterpolator>(g, roles, options); });
  r.levels = interpolator->levelCount();
  r.solve = bench::seconds([&] {
    if (fields == 3) r.info = interpolator->solve(values);
    else r.info[0] = interpolator->solve(values[0]);
  });
  r.cpu = cpuSeconds() - cpuStart;
  return r;
}

// Geometric mean of the residual's reduction per iteration.
double meanFactor(const LaplaceSolveInfo& info) {
  return std::pow(info.residualHistory.back() / info.residualHistory.front(), 1.0 / info.iterations);
}

void oneGrid() {
  const double loadBefore = bench::loadAverage();
  GridGeometry g;
  g.size = gSize;
  g.spacing = Eigen::Vector3d(1, 1, 1.5);
  const std::vector<CellRole> roles = ellipsoidRoles(g);
  std::int64_t freeCells = 0;
  for (CellRole r : roles) freeCells += r == CellRole::Free;
  const Run one = run(g, roles, LaplaceSolver::MultigridCG, 1);
  const Run three = run(g, roles, LaplaceSolver::MultigridCG, 3);
  const Run mg = run(g, roles, LaplaceSolver::Multigrid, 1);
  const Run cg = run(g, roles, LaplaceSolver::ConjugateGradient, 1);
  const double oneTotal = one.setup + one.solve, threeTotal = three.setup + three.solve;
  std::printf("| %d×%d×%d | %.2f M | %d | %.2f s + %.2f s = %.2f s (CPU %.1f s), %d it (×%.3f) | "
              "%.2f s + %.2f s = %.2f s (CPU %.1f s), %d/%d/%d it | %.2f s, %d cycles (×%.3f) | "
              "%.2f s (CPU %.1f s), %d it | %.1f× | %.1f× | %.1f× | %.1f → %.1f |",
              gSize.x(), gSize.y(), gSize.z(), freeCells / 1e6, one.levels, one.setup, one.solve, oneTotal, one.cpu,
              one.info[0].iterations, meanFactor(one.info[0]), three.setup, three.solve, threeTotal, three.cpu,
              three.info[0].iterations, three.info[1].iterations, three.info[2].iterations, mg.setup + mg.solve,
              mg.info[0].iterations, meanFactor(mg.info[0]), cg.solve, cg.cpu, cg.info[0].iterations,
              cg.solve / oneTotal, 3 * cg.solve / threeTotal, cg.solve / (mg.setup + mg.solve), loadBefore,
              bench::loadAverage());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> grids(argv + 1, argv + argc);
  if (grids.empty()) grids = {"64", "128"};
  std::printf("| grid | free cells | levels | MG-PCG, 1 field: setup + solve, iterations (mean residual factor) | "
              "MG-PCG, 3 fields at once: setup + solve, iterations | V-cycles: setup + solve, cycles (factor) | "
              "Jacobi-CG, 1 field: solve, iterations | CG / MG-PCG | 3 CG / MG-PCG 3 fields | CG / V-cycles | "
              "load | peak memory |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& grid : grids) {
    if (grid == "paper") gSize = Eigen::Vector3i(309, 839, 142);
    else if (grid == "half") gSize = Eigen::Vector3i(155, 420, 71);
    else if (grid == "64" || grid == "128") gSize = Eigen::Vector3i::Constant(std::stoi(grid));
    else {
      std::fprintf(stderr, "bench_transfer: unknown grid %s (64, 128, half or paper)\n", grid.c_str());
      return 2;
    }
    bench::inChild(oneGrid);
  }
  return 0;
}
