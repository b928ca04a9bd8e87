// Winding numbers (winding_number.h) against their exact sum and the known inside of a sphere, and closed
// surfaces from broken ones (closed_surface.h): an open cube, a sphere with a hole and a back-to-back fin,
// a closed sphere, and OpenSim's left hip bone (testdata/skeleton-opensim), each giving a closed
// 2-manifold that TetGen accepts, with the volume of the solid it stands for.
#include "vesalius/meshing/closed_surface.h"

#include "test_shapes.h"
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "vesalius/meshing/winding_number.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace vesalius::meshing {
namespace {

const std::string kPelvis = std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Geometry/l_pelvis.vtp";

// The cube [0, side]^3 as 12 outward triangles.
TriMesh cube(double side) {
  TriMesh m;
  m.V.resize(8, 3);
  for (int v = 0; v < 8; ++v) m.V.row(v) << side * (v & 1), side * ((v >> 1) & 1), side * ((v >> 2) & 1);
  m.F.resize(12, 3);
  m.F << 0, 2, 1, 1, 2, 3,  // z = 0
      4, 5, 6, 5, 7, 6,     // z = side
      0, 1, 4, 1, 5, 4,     // y = 0
      2, 6, 3, 3, 6, 7,     // y = side
      0, 4, 2, 2, 4, 6,     // x = 0
      1, 3, 5, 3, 7, 5;     // x = side
  return m;
}

TriMesh withoutFaces(const TriMesh& m, const std::vector<bool>& drop) {
  TriMesh out;
  out.V = m.V;
  out.F.resize(m.F.rows(), 3);
  Eigen::Index kept = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    if (!drop[std::size_t(f)]) out.F.row(kept++) = m.F.row(f);
  out.F.conservativeResize(kept, 3);
  return out;
}

// What TetGen needs: closed, 2-manifold, outward, no crossing triangles.
void expectTetgenReady(const TriMesh& s) {
  const EdgeCounts edges = countEdges(s.F);
  EXPECT_EQ(edges.boundary, 0);
  EXPECT_EQ(edges.nonManifold, 0);
  EXPECT_TRUE(selfIntersections(s.V, s.F).empty());
  EXPECT_GT(enclosedVolume(s.V, s.F), 0.0);
  EXPECT_NO_THROW(checkTetgenInput({RegionSurface{s, 1, "closed"}}));
}

ClosedSurfaceOptions closing(int targetFaces) {
  ClosedSurfaceOptions options;
  options.targetFaces = targetFaces;
  return options;
}

MatrixX3d randomPoints(int count, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  MatrixX3d P(count, 3);
  for (int i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) P(i, a) = lo[a] + u(rng) * (hi[a] - lo[a]);
  return P;
}

TEST(WindingNumber, SphereInsideIsOneOutsideZero) {
  const TriMesh s = test::sphere(4, 10.0);
  const MatrixX3d P = randomPoints(2000, Eigen::Vector3d::Constant(-15), Eigen::Vector3d::Constant(15), 1);
  const Eigen::VectorXd w = windingNumbers(s.V, s.F, P, WindingNumberOptions{0.0});
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double r = P.row(i).norm();
    if (r < 9.5 || r > 10.5) {
      EXPECT_NEAR(w[i], r < 9.5 ? 1.0 : 0.0, 1e-9) << r;  // the polygon dips 0.05 mm in
    }
  }
}

// The dipole tree against the exact sum, near and far, on a closed sphere and the broken hip bone.
TEST(WindingNumber, DipoleTreeMatchesTheExactSum) {
  const TriMesh s = test::sphere(5, 10.0);
  const MatrixX3d P = randomPoints(3000, Eigen::Vector3d::Constant(-20), Eigen::Vector3d::Constant(20), 2);
  const Eigen::VectorXd exact = windingNumbers(s.V, s.F, P, WindingNumberOptions{0.0});
  const double sphereError = (windingNumbers(s.V, s.F, P) - exact).cwiseAbs().maxCoeff();
  RecordProperty("sphere_max_error", std::to_string(sphereError));
  EXPECT_LT(sphereError, 0.02);

  const TriMesh pelvis = io::readTriMesh(kPelvis);
  const Eigen::Vector3d lo = pelvis.V.colwise().minCoeff(), hi = pelvis.V.colwise().maxCoeff();
  const MatrixX3d Q = randomPoints(3000, lo, hi, 3);
  const double pelvisError = (windingNumbers(pelvis.V, pelvis.F, Q) -
                              windingNumbers(pelvis.V, pelvis.F, Q, WindingNumberOptions{0.0}))
                                 .cwiseAbs()
                                 .maxCoeff();
  RecordProperty("pelvis_max_error", std::to_string(pelvisError));
  EXPECT_LT(pelvisError, 0.02);
}

TEST(WindingNumber, RefusesBadIndices) {
  const TriMesh s = test::sphere(1);
  MatrixX3i F = s.F;
  F(0, 0) = int(s.V.rows());
  EXPECT_THROW(windingNumbers(s.V, F, s.V), BadInput);
  EXPECT_THROW(windingNumbers(s.V, s.F, s.V, WindingNumberOptions{-1.0}), UsageError);
}

TEST(ClosedSurface, ClosedSphereKeepsItsVolume) {
  const TriMesh s = test::sphere(4, 10.0);
  const TriMesh closed = closedSurface(s);
  expectTetgenReady(closed);
  const double ratio = enclosedVolume(closed.V, closed.F) / enclosedVolume(s.V, s.F);
  RecordProperty("volume_ratio", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.01);
}

TEST(ClosedSurface, OpenCubeIsClosed) {
  std::vector<bool> drop(12, false);
  drop[2] = drop[3] = true;  // the top, z = side
  const TriMesh open = withoutFaces(cube(20.0), drop);
  ASSERT_EQ(countEdges(open.F).boundary, 4);
  const TriMesh closed = closedSurface(open, closing(2000));
  expectTetgenReady(closed);
  const double ratio = enclosedVolume(closed.V, closed.F) / 8000.0;
  RecordProperty("volume_ratio", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.03);
}

// A hole at the north pole (the cap above 0.9 r, 0.7% of the ball) and a fin of two back-to-back
// triangles on an edge at the equator, making it non-manifold: the hole closes, the fin goes.
TEST(ClosedSurface, SphereWithHoleAndFinIsClosed) {
  const TriMesh s = test::sphere(4, 10.0);
  std::vector<bool> drop(std::size_t(s.F.rows()), false);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    drop[std::size_t(f)] = s.V(s.F(f, 0), 2) > 9.0 && s.V(s.F(f, 1), 2) > 9.0 && s.V(s.F(f, 2), 2) > 9.0;
  TriMesh broken = withoutFaces(s, drop);
  Eigen::Index equator = 0;
  while (std::abs(s.V(broken.F(equator, 0), 2)) > 1.0) ++equator;
  const int a = broken.F(equator, 0), b = broken.F(equator, 1);
  broken.V.conservativeResize(broken.V.rows() + 1, 3);
  broken.V.row(broken.V.rows() - 1) = 1.5 * s.V.row(a);
  const int tip = int(broken.V.rows() - 1);
  broken.F.conservativeResize(broken.F.rows() + 2, 3);
  broken.F.row(broken.F.rows() - 2) << a, b, tip;
  broken.F.row(broken.F.rows() - 1) << b, a, tip;
  const EdgeCounts edges = countEdges(broken.F);
  ASSERT_GT(edges.boundary, 0);
  ASSERT_GT(edges.nonManifold, 0);

  const TriMesh closed = closedSurface(broken, closing(3000));
  expectTetgenReady(closed);
  const double ratio = enclosedVolume(closed.V, closed.F) / enclosedVolume(s.V, s.F);
  RecordProperty("volume_ratio", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.03);
  // The fin's tip, 5 mm out, is not part of the solid: nothing of the surface reaches beyond the sphere.
  EXPECT_LT(closed.V.rowwise().norm().maxCoeff(), 10.5);
}

// OpenSim's left hip bone (1 boundary edge, 5 non-manifold edges, crossing triangles; metres as read)
// gives a surface TetGen meshes, enclosing what the nearly closed original encloses.
TEST(ClosedSurface, OpenSimHipBoneIsMeshable) {
  const TriMesh pelvis = io::readTriMesh(kPelvis);
  const EdgeCounts edges = countEdges(pelvis.F);
  ASSERT_EQ(edges.boundary, 1);
  ASSERT_EQ(edges.nonManifold, 5);
  const TriMesh closed = closedSurface(pelvis, closing(1500));
  expectTetgenReady(closed);
  const double ratio = enclosedVolume(closed.V, closed.F) / enclosedVolume(pelvis.V, pelvis.F);
  RecordProperty("volume_ratio", std::to_string(ratio));
  EXPECT_NEAR(ratio, 1.0, 0.03);
  TetrahedralizeOptions options;
  options.targetTets = 5000;
  const TetMesh tets = tetrahedralize(closed, options, kPelvis);
  EXPECT_GT(tets.T.rows(), 1000);
}

TEST(ClosedSurface, RefusesWhatCannotBeClosed) {
  EXPECT_THROW(closedSurface(TriMesh{}), BadInput);
  TriMesh s = test::sphere(2, 10.0);
  s.V(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(closedSurface(s), BadInput);
  ClosedSurfaceOptions coarse;
  coarse.resolution = 4;
  EXPECT_THROW(closedSurface(test::sphere(2), coarse), UsageError);
}

}  // namespace
}  // namespace vesalius::meshing
