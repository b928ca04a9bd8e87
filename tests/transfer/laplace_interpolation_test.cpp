// Laplace interpolation (Dicko et al. 2013, §7): discretely harmonic functions are reproduced, the solvers agree,
// V-cycles contract, bad set-ups are refused, and neither threads nor solving three fields at once
// change the result.
#include "vesalius/transfer/laplace_interpolation.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

using Function = std::function<double(const Eigen::Vector3d&)>;

const LaplaceSolver kSolvers[] = {LaplaceSolver::MultigridCG, LaplaceSolver::Multigrid,
                                  LaplaceSolver::ConjugateGradient};

GridGeometry boxGeometry(int n, const Eigen::Vector3d& spacing = Eigen::Vector3d::Ones()) {
  GridGeometry g;
  g.size = Eigen::Vector3i::Constant(n);
  g.spacing = spacing;
  g.origin = Eigen::Vector3d(-10, 5, 3);
  return g;
}

// The grid's outer layer Fixed, the rest Free.
std::vector<CellRole> boxRoles(const GridGeometry& g) {
  std::vector<CellRole> roles(g.voxelCount(), CellRole::Free);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const bool edge = i == 0 || j == 0 || k == 0 || i == g.size.x() - 1 || j == g.size.y() - 1 ||
                          k == g.size.z() - 1;
        if (edge) roles[g.linearIndex(i, j, k)] = CellRole::Fixed;
      }
  return roles;
}

// Free inside a ball of radius `radius` mm around the grid's centre, Fixed in a shell 1.5 voxels thick
// around it, Excluded outside: the shape of a body inside its skin.
std::vector<CellRole> ballRoles(const GridGeometry& g, double radius) {
  const Eigen::Vector3d centre = g.indexToWorld((g.size.cast<double>().array() - 1).matrix() / 2);
  std::vector<CellRole> roles(g.voxelCount(), CellRole::Excluded);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const double d = (g.indexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm();
        CellRole& r = roles[g.linearIndex(i, j, k)];
        if (d < radius) r = CellRole::Free;
        else if (d < radius + 1.5 * g.spacing.maxCoeff()) r = CellRole::Fixed;
      }
  return roles;
}

// f at Fixed cells, `guess` at Free cells, NaN at Excluded cells (which must be left alone).
Grid<double> boundaryField(const GridGeometry& g, const std::vector<CellRole>& roles, const Function& f,
                           double guess = 0) {
  Grid<double> field(g, 0.0);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const std::int64_t v = g.linearIndex(i, j, k);
        field.values[v] = roles[v] == CellRole::Fixed ? f(g.indexToWorld(Eigen::Vector3d(i, j, k)))
                          : roles[v] == CellRole::Free ? guess
                                                       : std::nan("");
      }
  return field;
}

// max |field − f| over Free cells, relative to max |f| over Fixed cells.
double relativeError(const Grid<double>& field, const std::vector<CellRole>& roles, const Function& f) {
  const GridGeometry& g = field.geometry;
  double error = 0, scale = 0;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const std::int64_t v = g.linearIndex(i, j, k);
        const double exact = f(g.indexToWorld(Eigen::Vector3d(i, j, k)));
        if (roles[v] == CellRole::Free) error = std::max(error, std::abs(field.values[v] - exact));
        if (roles[v] == CellRole::Fixed) scale = std::max(scale, std::abs(exact));
      }
  return error / scale;
}

Grid<double> solved(const GridGeometry& g, const std::vector<CellRole>& roles, const Function& f,
                    LaplaceSolver solver, double tolerance = 1e-10) {
  LaplaceOptions options;
  options.solver = solver;
  options.tolerance = tolerance;
  LaplaceInterpolator interpolator(g, roles, options);
  Grid<double> field = boundaryField(g, roles, f);
  interpolator.solve(field);
  return field;
}

// Second differences of a quadratic are exact for any spacing, so these are discretely harmonic on
// every grid: Σ ∂² = 2 + 2 − 4 = 0, and the mixed terms have no second derivative along an axis.
double quadraticHarmonic(const Eigen::Vector3d& x) {
  return x.x() * x.x() + x.y() * x.y() - 2 * x.z() * x.z() + 0.5 * x.x() * x.y() * x.z() - 3 * x.y() + 40;
}

double linear(const Eigen::Vector3d& x) { return 2 * x.x() - 3 * x.y() + 0.5 * x.z() + 7; }

}  // namespace

TEST(LaplaceInterpolation, LinearFunctionIsReproducedInAnAnisotropicBox) {
  const GridGeometry g = boxGeometry(19, Eigen::Vector3d(0.8, 1.5, 2.5));
  const auto roles = boxRoles(g);
  for (LaplaceSolver solver : kSolvers) EXPECT_LT(relativeError(solved(g, roles, linear, solver), roles, linear), 1e-8);
}

TEST(LaplaceInterpolation, HarmonicQuadraticIsReproducedInABox) {
  for (const Eigen::Vector3d& spacing : {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, 1.7, 0.6)}) {
    const GridGeometry g = boxGeometry(33, spacing);
    const auto roles = boxRoles(g);
    for (LaplaceSolver solver : kSolvers)
      EXPECT_LT(relativeError(solved(g, roles, quadraticHarmonic, solver), roles, quadraticHarmonic), 1e-8)
          << "solver " << int(solver) << " spacing " << spacing.transpose();
  }
}

TEST(LaplaceInterpolation, HarmonicQuadraticIsReproducedInABallWithTheOutsideExcluded) {
  const GridGeometry g = boxGeometry(40, Eigen::Vector3d(1, 1, 1.4));
  const auto roles = ballRoles(g, 17);
  for (LaplaceSolver solver : kSolvers) {
    const Grid<double> field = solved(g, roles, quadraticHarmonic, solver);
    EXPECT_LT(relativeError(field, roles, quadraticHarmonic), 1e-8) << "solver " << int(solver);
    for (std::size_t v = 0; v < roles.size(); ++v)
      if (roles[v] == CellRole::Excluded) {
        ASSERT_TRUE(std::isnan(field.values[v]));  // left alone
      }
  }
}

// Fixed values on two opposite faces and zero flux through the four grid faces in between: the exact
// solution is linear across the slab, whatever the spacing.
TEST(LaplaceInterpolation, GridFacesWithoutFixedCellsAreZeroFlux) {
  GridGeometry g = boxGeometry(24, Eigen::Vector3d(0.7, 1.3, 2.1));
  g.size = Eigen::Vector3i(24, 11, 9);
  std::vector<CellRole> roles(g.voxelCount(), CellRole::Free);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      roles[g.linearIndex(0, j, k)] = roles[g.linearIndex(g.size.x() - 1, j, k)] = CellRole::Fixed;
  const Function ramp = [&](const Eigen::Vector3d& x) { return 3 * (x.x() - g.origin.x()) + 1; };
  for (LaplaceSolver solver : kSolvers) EXPECT_LT(relativeError(solved(g, roles, ramp, solver), roles, ramp), 1e-8);
}

TEST(LaplaceInterpolation, MultigridAndConjugateGradientAgree) {
  // Boundary values that are not harmonic inside: random on the ball's shell.
  const GridGeometry g = boxGeometry(48, Eigen::Vector3d(1, 1.2, 0.9));
  const auto roles = ballRoles(g, 20);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-5, 5);
  const Function noise = [&](const Eigen::Vector3d&) { return u(rng); };
  const Grid<double> boundary = boundaryField(g, roles, noise);
  std::vector<Grid<double>> results;
  for (LaplaceSolver solver : kSolvers) {
    LaplaceOptions options;
    options.solver = solver;
    LaplaceInterpolator interpolator(g, roles, options);
    results.push_back(boundary);
    interpolator.solve(results.back());
  }
  auto freeDifference = [&](const Grid<double>& a, const Grid<double>& b) {
    double diff = 0, size = 0;
    for (std::size_t v = 0; v < roles.size(); ++v)
      if (roles[v] == CellRole::Free) diff += std::pow(a.values[v] - b.values[v], 2), size += std::pow(b.values[v], 2);
    return std::sqrt(diff / size);
  };
  EXPECT_LT(freeDifference(results[0], results[2]), 1e-6);
  EXPECT_LT(freeDifference(results[1], results[2]), 1e-6);
}

namespace {

// Residual reduction per V-cycle on a 64³ box and a ball inside it, for MG-PCG (one V-cycle per
// iteration; the default) and for V-cycles alone.
std::vector<double> residualFactors(const std::vector<CellRole>& roles, LaplaceSolver solver) {
  const GridGeometry g = boxGeometry(64);
  LaplaceOptions options;
  options.solver = solver;
  options.tolerance = 1e-10;
  LaplaceInterpolator interpolator(g, roles, options);
  EXPECT_EQ(interpolator.levelCount(), 3);  // 64³, 32³, 16³ (solved by CG)
  Grid<double> field = boundaryField(g, roles, [](const Eigen::Vector3d& x) {
    return std::exp(x.x() / 20) * std::sin(x.y() / 10) + x.z();
  });
  const LaplaceSolveInfo info = interpolator.solve(field);
  std::vector<double> factors;
  for (std::size_t c = 1; c < info.residualHistory.size(); ++c)
    factors.push_back(info.residualHistory[c] / info.residualHistory[c - 1]);
  return factors;
}

}  // namespace

// Measured (V(3,3) with 2 boundary sweeps): mean factor 0.042 on the box and 0.075 on the ball, the worst
// single iteration 0.047 and 0.090. The computation is deterministic, so the bound is not flaky.
TEST(LaplaceInterpolation, EachMultigridPreconditionedIterationReducesTheResidualTenfold) {
  const GridGeometry g = boxGeometry(64);
  for (const auto& roles : {boxRoles(g), ballRoles(g, 28)}) {
    const std::vector<double> factors = residualFactors(roles, LaplaceSolver::MultigridCG);
    ASSERT_GE(factors.size(), 3u);
    for (double f : factors) EXPECT_LT(f, 0.1);
  }
}

// Measured: V-cycles alone settle at a factor of 0.105 (box, worst 0.138) and 0.25 (ball, worst 0.28),
// short of tenfold: the coarse levels see the Dirichlet boundary only to within their cell size
// (docs/methods/laplace-interpolation.md), which is why MG-PCG is the default. The bound guards
// against regressions.
TEST(LaplaceInterpolation, VCyclesAloneContractSteadily) {
  const GridGeometry g = boxGeometry(64);
  const std::vector<double> box = residualFactors(boxRoles(g), LaplaceSolver::Multigrid);
  const std::vector<double> ball = residualFactors(ballRoles(g, 28), LaplaceSolver::Multigrid);
  for (double f : box) EXPECT_LT(f, 0.15);
  for (double f : ball) EXPECT_LT(f, 0.3);
}

TEST(LaplaceInterpolation, AFreeRegionWithoutFixedCellsIsRefused) {
  // A pocket of free cells walled off from the fixed box boundary by an Excluded shell.
  const GridGeometry g = boxGeometry(16);
  std::vector<CellRole> roles = boxRoles(g);
  for (int k = 5; k <= 9; ++k)
    for (int j = 5; j <= 9; ++j)
      for (int i = 5; i <= 9; ++i)
        if (i == 5 || i == 9 || j == 5 || j == 9 || k == 5 || k == 9) roles[g.linearIndex(i, j, k)] = CellRole::Excluded;
  try {
    LaplaceInterpolator interpolator(g, roles);
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("free region of 27 cells, the first at voxel (6, 6, 6)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(LaplaceInterpolator(g, std::vector<CellRole>(g.voxelCount(), CellRole::Free)), BadInput);
}

TEST(LaplaceInterpolation, BadGeometryAndFieldsAreRefused) {
  GridGeometry g = boxGeometry(8);
  const auto roles = boxRoles(g);
  EXPECT_THROW(LaplaceInterpolator(g, std::vector<CellRole>(10, CellRole::Fixed)), BadInput);
  GridGeometry sheared = g;
  sheared.direction(0, 1) = 0.3;
  EXPECT_THROW(LaplaceInterpolator(sheared, roles), BadInput);
  LaplaceInterpolator interpolator(g, roles);
  Grid<double> wrongSize(boxGeometry(9), 0.0);
  EXPECT_THROW(interpolator.solve(wrongSize), BadInput);
  Grid<double> field = boundaryField(g, roles, linear);
  field.values[0] = std::nan("");  // a Fixed corner
  EXPECT_THROW(interpolator.solve(field), BadInput);
}

TEST(LaplaceInterpolation, HittingTheIterationLimitIsANumericalFailure) {
  const GridGeometry g = boxGeometry(24);
  const auto roles = boxRoles(g);
  LaplaceOptions options;
  options.solver = LaplaceSolver::ConjugateGradient;
  options.maxCgIterations = 3;
  LaplaceInterpolator interpolator(g, roles, options);
  Grid<double> field = boundaryField(g, roles, quadraticHarmonic);
  EXPECT_THROW(interpolator.solve(field), NumericalFailure);
}

TEST(LaplaceInterpolation, AnExactInitialGuessNeedsNoIterationAndZeroDataGivesZero) {
  const GridGeometry g = boxGeometry(20);
  const auto roles = boxRoles(g);
  LaplaceInterpolator interpolator(g, roles);
  Grid<double> field = boundaryField(g, roles, linear);
  for (int k = 0; k < 20; ++k)
    for (int j = 0; j < 20; ++j)
      for (int i = 0; i < 20; ++i) field.at(i, j, k) = linear(g.indexToWorld(Eigen::Vector3d(i, j, k)));
  EXPECT_EQ(interpolator.solve(field).iterations, 0);
  Grid<double> zero = boundaryField(g, roles, [](const Eigen::Vector3d&) { return 0.0; }, 5.0);
  interpolator.solve(zero);
  for (double v : zero.values) EXPECT_EQ(v, 0.0);
}

TEST(LaplaceInterpolation, ResultsDoNotDependOnTheThreadCount) {
  const GridGeometry g = boxGeometry(40, Eigen::Vector3d(1, 1, 1.5));
  const auto roles = ballRoles(g, 22);
  const Function f = [](const Eigen::Vector3d& x) { return std::sin(x.x() / 7) * std::cos(x.z() / 5) + x.y(); };
  for (LaplaceSolver solver : kSolvers) {
    Grid<double> one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = solved(g, roles, f, solver, 1e-8);
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = solved(g, roles, f, solver, 1e-8);
    }
    for (std::size_t v = 0; v < roles.size(); ++v)
      if (roles[v] != CellRole::Excluded) {
        ASSERT_EQ(one.values[v], two.values[v]) << "solver " << int(solver);
      }
  }
}

// The 3-wide solve carries its own α, β and stopping per field, so each field must come out bitwise as
// when solved alone — including a field that starts close to its solution and stops iterations earlier
// than the others, and one whose fixed values are all zero.
TEST(LaplaceInterpolation, ThreeFieldsAtOnceGiveBitwiseTheSingleSolves) {
  const GridGeometry g = boxGeometry(36, Eigen::Vector3d(1, 1.2, 1.5));
  const auto roles = ballRoles(g, 16);
  const Function f = [](const Eigen::Vector3d& x) {
    return std::sin(x.x() / 6) * std::cos(x.z() / 4) + 0.1 * x.y() * x.y();
  };
  const Function zero = [](const Eigen::Vector3d&) { return 0.0; };
  const Grid<double> nearSolution = solved(g, roles, f, LaplaceSolver::ConjugateGradient, 1e-5);
  for (LaplaceSolver solver : kSolvers) {
    LaplaceOptions options;
    options.solver = solver;
    LaplaceInterpolator interpolator(g, roles, options);
    const std::array<Grid<double>, 3> start = {boundaryField(g, roles, f, 0.5), nearSolution,
                                               boundaryField(g, roles, zero, 0.5)};
    std::array<Grid<double>, 3> together = start;
    const std::array<LaplaceSolveInfo, 3> info = interpolator.solve(together);
    EXPECT_LT(info[1].iterations, info[0].iterations) << "solver " << int(solver);  // they stop apart
    EXPECT_EQ(info[2].iterations, 0);
    for (int c = 0; c < 3; ++c) {
      Grid<double> alone = start[c];
      const LaplaceSolveInfo single = interpolator.solve(alone);
      EXPECT_EQ(single.iterations, info[c].iterations) << "solver " << int(solver) << " field " << c;
      EXPECT_EQ(single.residualHistory, info[c].residualHistory) << "solver " << int(solver) << " field " << c;
      EXPECT_EQ(single.relativeResidual, info[c].relativeResidual);
      for (std::size_t v = 0; v < roles.size(); ++v)
        if (roles[v] != CellRole::Excluded) {
          ASSERT_EQ(alone.values[v], together[c].values[v]) << "solver " << int(solver) << " field " << c;
        }
    }
  }
}
