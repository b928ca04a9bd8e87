// Benchmarks of the plastic-strain fitter (Wang et al. 2021) on the SOFA liver template tetrahedralized at about
// 35k tets (the paper's hand-muscle size) with 150 ICP markers:
//   1. one search-direction solve, Woodbury (eq. 14) against conjugate gradients on the same H (Table 1);
//   2. a whole fit from the placed template to markers on a known plastic deformation of it.
// Each runs in a child process so that its peak memory is its own.
#include "bench_support.h"
#include "test_plastic_fields.h"

#include "vesalius/core/transparent_huge_pages.h"
#include "vesalius/fit/equilibrium_jacobian.h"
#include "vesalius/fit/initial_placement.h"
#include "vesalius/fit/plastic_fit.h"
#include "vesalius/fit/plastic_laplacian.h"
#include "vesalius/fit/surface_projection.h"
#include "vesalius/fit/woodbury.h"

#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fem/static_equilibrium.h"

#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/meshing/tetrahedralize.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

using namespace vesalius;

namespace {

TetMesh liverTemplate() {
  TriMesh surface = io::readTriMesh(VESALIUS_TESTDATA "/liver/liver.obj");
  surface.V *= 25.0;  // the file's units are arbitrary; about 160 mm wide in mm
  meshing::TetrahedralizeOptions options;
  options.targetTets = 35000;
  return meshing::tetrahedralize(surface, options, "liver.obj");
}

struct Case {
  TetMesh templ;
  MatrixX3d markers;  // 150 points spread over the deformed surface
};

Case liverCase() {
  Case c{liverTemplate(), {}};
  const PlasticFem fem(c.templ.V, c.templ.T, StableNeoHookean::fromYoungPoisson(1.0, 0.45));
  const MatrixX3d truth = PlasticFem::unflatten(
      solveStaticEquilibrium(fem, test::knownPlasticField(c.templ), PointSprings{}, PlasticFem::flatten(c.templ.V)).x);
  TriMesh surface;
  surface.V = truth;
  surface.F = tetBoundary(c.templ.T);
  c.markers = meshing::spreadSurfacePoints(surface, 150, 1);
  return c;
}

fit::Placement place(const Case& c) {
  TriMesh surface;
  surface.V = c.templ.V;
  surface.F = tetBoundary(c.templ.T);
  return fit::placeTemplate(surface, MatrixX3d(), MatrixX3d(), c.markers);
}

// `bench_fit woodbury` leaves the conjugate-gradient baseline out (it takes minutes), to work on Woodbury.
bool withBaseline = true;

void searchDirection() {
  const Case c = liverCase();
  const fit::Placement p = place(c);
  const Eigen::VectorXd x = PlasticFem::flatten(p.transform.apply(c.templ.V));
  Eigen::VectorXd s(6 * c.templ.T.rows());
  for (Eigen::Index t = 0; t < c.templ.T.rows(); ++t) s.segment<6>(6 * t) = p.transform.scale * identityPlasticStrain();
  const PlasticFem fem(c.templ.V, c.templ.T, StableNeoHookean::fromYoungPoisson(1.0, 0.45));
  const fit::SurfaceProjection surface(c.templ.T);
  const auto active = surface.closestPoints(x, c.markers, 1e3);
  const fit::RigidGauge gauge(active, c.templ.V, x);
  SparseCholesky cholesky;
  double prep = 0;
  std::optional<fit::ConstraintJacobian> Z;
  prep = bench::seconds([&] {
    const fit::EquilibriumJacobian J(fem.stiffness(x, s, true), fem.plasticForceJacobian(x, s), x, &gauge, cholesky);
    Z.emplace(J.constraintJacobian(fit::constraintRows(active, fem.vertexCount())));
  });
  const Eigen::SparseMatrix<double> Lsc = fit::tetAdjacencyLaplacian(c.templ.T);
  const Eigen::VectorXd h = -Z->transposeTimes(fit::constraintResiduals(active, x));
  const Eigen::Index rows = Z->rows();
  fit::ConjugateGradientResult cg{Eigen::VectorXd::Zero(h.size()), 0, 1.0};
  const double tCg =
      withBaseline ? bench::seconds([&] { cg = fit::solveConjugateGradient(Lsc, *Z, h, 1e-6, 20000); }) : 0.0;
  Eigen::VectorXd yWoodbury;
  double tFactor = 0, tSetup = 0, tSolve = 0;
  long setupFaults = 0;
  const double cpuBefore = bench::cpuSeconds();
  const double tWoodbury = bench::seconds([&] {
    std::optional<fit::SmoothnessBaseSolver> base;
    tFactor = bench::seconds([&] { base.emplace(Lsc); });
    std::optional<fit::WoodburySolver> solver;
    const long faultsBefore = bench::pageFaults();
    tSetup = bench::seconds([&] { solver.emplace(*base, std::move(*Z)); });
    setupFaults = bench::pageFaults() - faultsBefore;
    tSolve = bench::seconds([&] { yWoodbury = solver->solve(Eigen::MatrixXd(h)).col(0); });
  });
  const double cpuWoodbury = bench::cpuSeconds() - cpuBefore;
  std::fprintf(stderr,
               "Woodbury: %.2f s of CPU; factor L %.2f s, setup (Z (L²)⁺ Zᵀ and the capacitance LU) %.2f s with %ld page faults, "
               "refined solve %.2f s; load %.1f\n",
               cpuWoodbury, tFactor, tSetup, setupFaults, tSolve, bench::loadAverage());
  // Wang et al. 2021 factors B "once for the entire optimization" (§3.4): a direction after the first costs the
  // Woodbury time less the factor of L, the second ratio.
  std::printf("| one search direction, %ld tets (6#T = %ld), %ld constraint rows | %.1f s | %.1f s (%d iterations, "
              "residual %.1e, %.1e from Woodbury's) | %.2f s (%.2f s with L factored) | %.0f× (%.0f×) |",
              long(c.templ.T.rows()), long(6 * c.templ.T.rows()), long(rows), prep, tCg, cg.iterations,
              cg.relativeResidual, (cg.y - yWoodbury).norm() / yWoodbury.norm(), tWoodbury, tWoodbury - tFactor,
              tCg / tWoodbury, tCg / (tWoodbury - tFactor));
}

// The whole fit's options: the defaults, or with the ICP-gain rule off (`fit-all`).
fit::FitOptions wholeFitOptions;

void wholeFit() {
  const Case c = liverCase();
  const fit::Placement p = place(c);
  Eigen::VectorXd s0(6 * c.templ.T.rows());
  for (Eigen::Index t = 0; t < c.templ.T.rows(); ++t) s0.segment<6>(6 * t) = p.transform.scale * identityPlasticStrain();
  fit::FitMarkers markers;
  markers.icp = c.markers;
  const fit::SurfaceProjection surface(c.templ.T);
  const Eigen::VectorXd before = surface.distances(PlasticFem::flatten(p.transform.apply(c.templ.V)), c.markers);
  fit::FitResult r;
  const double t = bench::seconds(
      [&] { r = fit::fitPlasticStrains(c.templ, p.transform.apply(c.templ.V), s0, markers, wholeFitOptions); });
  const bool gainRule = wholeFitOptions.minIcpGain > 0 || wholeFitOptions.minIcpGainMm > 0;
  std::printf("| whole fit, %ld tets, %ld ICP markers%s | %zu iterations | ICP error %.2f / %.2f mm -> %.3f / %.3f mm "
              "| %.1f s |",
              long(c.templ.T.rows()), long(c.markers.rows()), gainRule ? "" : ", ICP-gain rule off", r.history.size(),
              before.mean(), before.maxCoeff(), r.icpErrors.mean(), r.icpErrors.maxCoeff(), t);
  // The history on stderr, all digits: a change meant to keep the fit must keep these.
  for (const fit::FitIteration& it : r.history)
    std::fprintf(stderr, "%s %d: ICP error %.17g / %.17g mm, step %.3g, %.1f s\n", it.stage.c_str(), it.iteration,
                 it.meanIcpError, it.maxIcpError, it.step, it.seconds);
  for (const fit::FitStageEnd& e : r.stageEnds)
    std::fprintf(stderr, "stage %s: %d iterations, ended by %s\n", e.stage.c_str(), e.iterations, e.reason.c_str());
}

}  // namespace

// bench_fit [direction|woodbury|fit|fit-all]: one part only (the conjugate-gradient baseline alone takes
// minutes; woodbury is the direction without it); fit-all is the whole fit with the ICP-gain rule off.
int main(int argc, char** argv) {
  restartWithTransparentHugePages(argv);  // as the CLI runs
  std::string only = argc > 1 ? argv[1] : "";
  if (only == "fit-all") {
    wholeFitOptions.minIcpGain = 0;
    wholeFitOptions.minIcpGainMm = 0;
    only = "fit";
  }
  if (only == "woodbury") {
    withBaseline = false;
    only = "direction";
  }
  if (only.empty() || only == "direction") {
    std::printf("| run | Z (prep) | conjugate gradients | Woodbury | ratio | peak memory |\n|---|---|---|---|---|---|\n");
    bench::inChild(searchDirection);
  }
  if (only.empty() || only == "fit") {
    std::printf("\n| run | iterations | marker error (mean / max) | time | peak memory |\n|---|---|---|---|---|\n");
    bench::inChild(wholeFit);
  }
  return 0;
}
