// TetGen within bounds: the tet target kept on surfaces of any density (tet_budget.h), and the budgets of
// tetrahedralize.h that stop a run which would not end (options refused up front, points capped during it).
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/tet_budget.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <iostream>

namespace vesalius {
namespace {

using meshing::TetrahedralizeOptions;

// An ellipsoid of 40 x 60 x 30 mm semi-axes, 8 * 4^levels triangles.
TriMesh ellipsoid(int levels) {
  TriMesh m = test::sphere(levels);
  m.V = m.V * Eigen::Vector3d(40, 60, 30).asDiagonal();
  return m;
}

// From 128 to 131,072 triangles, one target: the tets stay within twice it (and above half of it), and the
// coarsened surface keeps the volume the given one encloses to within a few per cent.
TEST(TetBudget, TargetHeldOnSurfacesOfAnyDensity) {
  TetrahedralizeOptions options;
  options.targetTets = 5000;
  for (int levels = 2; levels <= 7; ++levels) {
    const TriMesh surface = ellipsoid(levels);
    const auto start = std::chrono::steady_clock::now();
    const meshing::BudgetedTets result = meshing::tetrahedralizeWithinBudget(surface, options, "ellipsoid");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double volume = tetVolumes(result.tets.V, result.tets.T).sum(), exact = enclosedVolume(surface.V, surface.F);
    std::cout << surface.F.rows() << " triangles: " << result.surfaceFaces << " given to TetGen ("
              << result.coarsenings << " coarsenings), " << result.tets.T.rows() << " tets, volume "
              << volume / exact << " of the surface's, " << seconds << " s\n";
    EXPECT_LE(result.tets.T.rows(), 2 * options.targetTets) << surface.F.rows() << " triangles";
    EXPECT_GE(result.tets.T.rows(), options.targetTets / 2) << surface.F.rows() << " triangles";
    EXPECT_NEAR(volume / exact, 1.0, 0.05);
    EXPECT_EQ(tetQualityReport(result.tets.V, result.tets.T).inverted, 0);
    if (surface.F.rows() <= meshing::facesForTets(options.targetTets)) { EXPECT_EQ(result.coarsenings, 0); }
  }
  options.targetTets = 0;
  EXPECT_THROW(meshing::tetrahedralizeWithinBudget(ellipsoid(2), options), UsageError);
}

// Small targets on real organ shapes (the shipped templates: 274 to 3,000 triangles): at 200 triangles
// TetGen's refinement still gives more than twice a target of a few thousand, so the halving goes on below.
TEST(TetBudget, SmallTargetsHeldOnOrganTemplates) {
  const std::string templates = std::string(VESALIUS_TESTDATA) + "/../templates/organs/";
  for (const char* organ : {"liver", "spleen", "kidney_left", "kidney_right"}) {
    const TriMesh surface = io::readTriMesh(templates + organ + ".obj");
    const double exact = enclosedVolume(surface.V, surface.F);
    for (long target : {500L, 1000L, 2000L}) {
      TetrahedralizeOptions options;
      options.targetTets = target;
      const meshing::BudgetedTets result = meshing::tetrahedralizeWithinBudget(surface, options, organ);
      const double volume = tetVolumes(result.tets.V, result.tets.T).sum();
      std::cout << organ << ", target " << target << ": " << result.surfaceFaces << " triangles given to TetGen, "
                << result.tets.T.rows() << " tets, volume " << volume / exact << " of the surface's\n";
      EXPECT_LE(result.tets.T.rows(), 2 * target) << organ;
      EXPECT_EQ(tetQualityReport(result.tets.V, result.tets.T).inverted, 0) << organ;
    }
  }
}

// A surface too coarse to decimate further and a target below what its triangles allow: TetGen's
// refinement splits the surface triangles it encroaches on. The surface kept as given (-Y) is then taken
// where it gives fewer tets: never more tets than the plain run, the volume kept, none inverted.
TEST(TetBudget, ASurfaceDecimationCannotTakeIsKeptWhenThatGivesFewerTets) {
  for (int levels = 0; levels <= 1; ++levels) {  // at most 50 triangles: nothing to decimate
    // Flat (5 mm thick), so that TetGen's refinement splits its triangles.
    TriMesh surface = test::sphere(levels);
    surface.V = surface.V * Eigen::Vector3d(40, 60, 5).asDiagonal();
    TetrahedralizeOptions options;
    options.targetTets = surface.F.rows() / 8;
    options.keepSurfaceOverBudget = true;
    const meshing::BudgetedTets result = meshing::tetrahedralizeWithinBudget(surface, options, "ellipsoid");
    const TetMesh plain = meshing::tetrahedralize(surface, options, "ellipsoid");
    TetrahedralizeOptions keep = options;
    keep.keepSurface = true;
    options.keepSurfaceOverBudget = false;
    EXPECT_FALSE(meshing::tetrahedralizeWithinBudget(surface, options, "ellipsoid").surfaceKept);  // only when asked
    const TetMesh kept = meshing::tetrahedralize(surface, keep, "ellipsoid");
    const double volume = tetVolumes(result.tets.V, result.tets.T).sum(), exact = enclosedVolume(surface.V, surface.F);
    std::cout << surface.F.rows() << " triangles, " << options.targetTets << " tets asked: " << result.tets.T.rows()
              << " tets (surface kept: " << result.surfaceKept << "; TetGen refining the surface: " << plain.T.rows()
              << ", keeping it: " << kept.T.rows() << "), volume " << volume / exact << " of the surface's\n";
    EXPECT_EQ(result.surfaceFaces, surface.F.rows());
    ASSERT_GT(plain.T.rows(), 2 * options.targetTets);  // over the budget: the case this test is about
    EXPECT_EQ(result.tets.T.rows(), std::min(plain.T.rows(), kept.T.rows()));
    EXPECT_EQ(result.surfaceKept, kept.T.rows() < plain.T.rows());
    EXPECT_NEAR(volume / exact, 1.0, 1e-9);
    EXPECT_EQ(tetQualityReport(result.tets.V, result.tets.T).inverted, 0);
  }
}

// A radius-edge bound TetGen may never meet, and a volume bound needing more tets than the budget, are
// refused before TetGen runs.
TEST(TetBudget, UnendingBoundsAreRefusedUpFront) {
  TetrahedralizeOptions options;
  options.radiusEdge = 0.5;
  EXPECT_THROW(meshing::tetrahedralize(ellipsoid(2), options), UsageError);
  options.radiusEdge = 1.5;
  options.maxVolume = 1e-12;
  const auto start = std::chrono::steady_clock::now();
  try {
    meshing::tetrahedralize(ellipsoid(2), options, "ellipsoid");
    ADD_FAILURE() << "a volume bound of 1e-12 mm^3 was accepted";
  } catch (const UsageError& e) {
    std::cout << e.what() << '\n';
    EXPECT_NE(std::string(e.what()).find("ellipsoid: a volume bound of 1e-12 mm^3 needs at least"), std::string::npos);
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  options.maxVolume = 0;
  options.targetTets = 6'000'000;
  EXPECT_THROW(meshing::tetrahedralize(ellipsoid(2), options), UsageError);
}

// Bounds that pass the up-front check but need more points than the budget: TetGen stops at the budget
// and the mesh, which did not meet its bounds, is refused with one line naming the surface.
TEST(TetBudget, RunStoppedAtItsPointBudget) {
  TetrahedralizeOptions options;
  options.maxTets = 10000;  // 2,000 points
  options.maxVolume = 0.5;  // at least 4,826 tets in the 2,413 mm^3 of this 8 x 12 x 6 mm ellipsoid
  TriMesh small = test::sphere(3);
  small.V = small.V * Eigen::Vector3d(8, 12, 6).asDiagonal();
  try {
    meshing::tetrahedralize(small, options, "small ellipsoid");
    ADD_FAILURE() << "a run past its budget was accepted";
  } catch (const BadInput& e) {
    std::cout << e.what() << '\n';
    EXPECT_NE(std::string(e.what()).find("small ellipsoid: TetGen stopped after adding its budget of 2000 points"),
              std::string::npos);
  }
  options.maxTets = 5'000'000;
  const TetMesh within = meshing::tetrahedralize(small, options, "small ellipsoid");
  std::cout << "with the default budget: " << within.T.rows() << " tets\n";
  EXPECT_GT(within.T.rows(), 4826);
}

}  // namespace
}  // namespace vesalius
