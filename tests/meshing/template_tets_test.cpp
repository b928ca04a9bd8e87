// Template tets (meshing/template_tets.h): the tets of closed surfaces of any density at a tet target (the
// refit remesher of fit/template_fit.h), surface templates closed first where they are broken, and flat
// templates refused before TetGen.
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/meshing/template_tets.h"

#include "expect_bad_input.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace vesalius {
namespace {

using meshing::TemplateTetsOptions;

// An ellipsoid of 40 x 60 x 30 mm semi-axes, 8 * 4^levels triangles.
TriMesh ellipsoid(int levels) {
  TriMesh m = test::sphere(levels);
  m.V = m.V * Eigen::Vector3d(40, 60, 30).asDiagonal();
  return m;
}

// A dumbbell 180 mm long: its cross-sections shrink to a waist of 0.55 of its ends' (not convex).
TriMesh dumbbell(int levels) {
  TriMesh m = test::sphere(levels);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const double x = m.V(v, 0), waist = 40 * (0.55 + 0.45 * x * x);
    m.V.row(v) = Eigen::RowVector3d(90 * x, waist * m.V(v, 1), waist * m.V(v, 2));
  }
  return m;
}

void expectClosedAndUncrossed(const TriMesh& m, const std::string& what) {
  const EdgeCounts edges = countEdges(m.F);
  EXPECT_EQ(edges.boundary, 0) << what;
  EXPECT_EQ(edges.nonManifold, 0) << what;
  EXPECT_TRUE(selfIntersections(m.V, m.F).empty()) << what;
}

// Within twice the target and above half of it; beyond twice it only where the surface was coarsened to the
// 200 triangles tet_budget.h stops at (facesForTets).
void expectWithinBudget(long tets, long faces, long target, const std::string& what) {
  if (faces > meshing::facesForTets(1)) {
    EXPECT_LE(tets, 2 * target) << what;
  }
  EXPECT_GE(tets, target / 2) << what;
}

// A bean 140 mm long, bent along y (not convex, no waist).
TriMesh bean(int levels) {
  TriMesh m = test::sphere(levels);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const Eigen::RowVector3d p = m.V.row(v);
    m.V.row(v) = Eigen::RowVector3d(70 * p.x(), 45 * p.y() + 12 * p.x() * p.x(), 35 * p.z());
  }
  return m;
}

// Three shapes, fine and coarse: at a target the tets stay within twice it and above half of it, and fill the
// surface's volume; at a face count TetGen is given about that many triangles.
TEST(TemplateTets, ClosedSurfacesKeepTheTetTarget) {
  for (const auto& [name, surface] : {std::pair<std::string, TriMesh>{"ellipsoid", ellipsoid(5)},
                                      {"bean", bean(5)}, {"dumbbell", dumbbell(5)},
                                      {"coarse dumbbell", dumbbell(2)}}) {
    TemplateTetsOptions options;
    options.targetTets = 3000;
    const meshing::BudgetedTets budget = meshing::closedSurfaceTets(surface, options, name);
    const double volume = tetVolumes(budget.tets.V, budget.tets.T).sum(), exact = enclosedVolume(surface.V, surface.F);
    std::cout << name << " (" << surface.F.rows() << " triangles), target " << options.targetTets << ": "
              << budget.tets.T.rows() << " tets from " << budget.surfaceFaces << " triangles, volume " << volume / exact
              << " of the surface's\n";
    expectWithinBudget(budget.tets.T.rows(), budget.surfaceFaces, options.targetTets, name);
    EXPECT_NEAR(volume / exact, 1.0, 0.05) << name;
    EXPECT_EQ(tetQualityReport(budget.tets.V, budget.tets.T).inverted, 0) << name;

    options.faces = 400;
    const meshing::BudgetedTets faces = meshing::closedSurfaceTets(surface, options, name);
    std::cout << name << " at " << options.faces << " triangles: " << faces.surfaceFaces << " given to TetGen, "
              << faces.tets.T.rows() << " tets\n";
    if (surface.F.rows() <= options.faces) {
      EXPECT_EQ(faces.surfaceFaces, surface.F.rows()) << name;  // a coarser surface is kept as it is
      EXPECT_EQ(faces.coarsenings, 0) << name;
    } else {
      EXPECT_LE(faces.surfaceFaces, 2 * options.faces) << name;  // decimate_surface.h tries up to twice the count
      EXPECT_GE(faces.surfaceFaces, options.faces / 2) << name;
      EXPECT_EQ(faces.coarsenings, 1) << name;
    }
    EXPECT_NEAR(tetVolumes(faces.tets.V, faces.tets.T).sum() / exact, 1.0, 0.05) << name;
  }
  TemplateTetsOptions none;
  none.targetTets = 0;
  EXPECT_THROW(meshing::closedSurfaceTets(ellipsoid(2), none), UsageError);
  none.faces = 400;
  EXPECT_THROW(meshing::closedSurfaceTets(ellipsoid(2), none), UsageError);
}

// A closed template is tetrahedralized as it is; a template with a hole is closed first, says what was
// wrong, and its closed surface (what the tets fill) is returned to be carried by the fit.
TEST(TemplateTets, BrokenTemplatesAreClosedFirst) {
  for (const auto& [name, closed] : {std::pair<std::string, TriMesh>{"ellipsoid", ellipsoid(4)},
                                     {"dumbbell", dumbbell(4)}}) {
    TemplateTetsOptions options;
    options.targetTets = 2000;
    const meshing::TemplateTets asItIs = meshing::templateTets(closed, options, name);
    EXPECT_FALSE(asItIs.repair) << name;
    EXPECT_EQ(asItIs.surface.V, closed.V) << name;
    EXPECT_EQ(asItIs.surface.F, closed.F) << name;
    expectWithinBudget(asItIs.tets.T.rows(), asItIs.tetrahedralizedFaces, options.targetTets, name);

    TriMesh open = closed;
    open.F = closed.F.topRows(closed.F.rows() - 6);  // a hole of six triangles
    const meshing::TemplateTets repaired = meshing::templateTets(open, options, name);
    ASSERT_TRUE(repaired.repair) << name;
    EXPECT_EQ(repaired.repair->boundaryEdges, countEdges(open.F).boundary) << name;
    EXPECT_GT(repaired.repair->boundaryEdges, 0) << name;
    EXPECT_EQ(repaired.repair->nonManifoldEdges, 0) << name;
    EXPECT_EQ(repaired.repair->crossingTrianglePairs, 0) << name;
    EXPECT_EQ(repaired.repair->closedTriangles, repaired.surface.F.rows()) << name;
    expectClosedAndUncrossed(repaired.surface, name);
    const double volume = tetVolumes(repaired.tets.V, repaired.tets.T).sum(),
                 exact = enclosedVolume(closed.V, closed.F);
    std::cout << name << " with a hole: " << repaired.repair->boundaryEdges << " boundary edges, closed into "
              << repaired.repair->closedTriangles << " triangles, " << repaired.tets.T.rows() << " tets, volume "
              << volume / exact << " of the closed original's\n";
    // The winding number fills the hole as the surface around it would: the volume within the grid's voxels.
    EXPECT_NEAR(volume / exact, 1.0, 0.05) << name;
    expectWithinBudget(repaired.tets.T.rows(), repaired.tetrahedralizedFaces, options.targetTets, name);
  }
}

// Flat templates have no inside for TetGen to fill: refused, naming the template, before TetGen runs.
TEST(TemplateTets, FlatTemplatesAreRefused) {
  TriMesh plate = ellipsoid(3);
  plate.V.col(2) *= 1e-9;
  test::expectOneLineBadInput("plate.obj", "the template's vertices lie in one plane",
                              [&] { meshing::templateTets(plate, {}, "plate.obj"); });
  // A bent sheet twice over, back to back: not in one plane, but closed around nothing.
  TriMesh sheet;
  const int n = 12;
  sheet.V.resize(2 * (n + 1), 3);
  for (int i = 0; i <= n; ++i) {
    const double a = EIGEN_PI * i / n;
    sheet.V.row(2 * i) << 50 * std::cos(a), 50 * std::sin(a), 0;
    sheet.V.row(2 * i + 1) << 50 * std::cos(a), 50 * std::sin(a), 80;
  }
  sheet.F.resize(4 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1, c = 2 * i + 2, d = 2 * i + 3;
    sheet.F.row(4 * i) << a, c, b;
    sheet.F.row(4 * i + 1) << b, c, d;
    sheet.F.row(4 * i + 2) << a, b, c;
    sheet.F.row(4 * i + 3) << b, d, c;
  }
  test::expectOneLineBadInput("sheet.stl", "the template encloses ",
                              [&] { meshing::templateTets(sheet, {}, "sheet.stl"); });
}

}  // namespace
}  // namespace vesalius
