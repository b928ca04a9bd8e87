// Dirichlet values from scattered points (the skin's displacements as boundary conditions, Dicko et al. 2013, §7).
#include "vesalius/transfer/point_constraints.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

GridGeometry smallGrid() {
  GridGeometry g;
  g.size = Eigen::Vector3i(6, 5, 4);
  g.origin = Eigen::Vector3d(10, -4, 2);
  g.spacing = Eigen::Vector3d(2, 1, 0.5);
  g.direction << 0, -1, 0, 1, 0, 0, 0, 0, 1;  // a rotation about z
  return g;
}

}  // namespace

TEST(PointConstraints, NearestFixesTheVoxelUnderThePoint) {
  const GridGeometry g = smallGrid();
  MatrixX3d P(2, 3);
  P.row(0) = g.indexToWorld(Eigen::Vector3d(2, 3, 1)).transpose();
  P.row(1) = g.indexToWorld(Eigen::Vector3d(4.3, 0.6, 2.8)).transpose();
  Eigen::MatrixXd values(2, 2);
  values << 1, 2, 3, 4;
  const VoxelConstraints c = splatPointValues(g, P, values, {SplatMethod::Nearest});
  ASSERT_EQ(c.voxels.size(), 2u);
  EXPECT_EQ(c.voxels[0], g.linearIndex(2, 3, 1));
  EXPECT_EQ(c.voxels[1], g.linearIndex(4, 1, 3));
  EXPECT_EQ(c.values.row(0), values.row(0));
  EXPECT_EQ(c.values.row(1), values.row(1));
}

TEST(PointConstraints, TrilinearSplatAveragesThePointsByWeight) {
  const GridGeometry g = smallGrid();
  MatrixX3d P(2, 3);
  P.row(0) = g.indexToWorld(Eigen::Vector3d(1.25, 2, 3)).transpose();  // on a voxel row: 2 voxels
  P.row(1) = g.indexToWorld(Eigen::Vector3d(1.75, 2, 3)).transpose();
  Eigen::MatrixXd values(2, 1);
  values << 1, 3;
  const VoxelConstraints c = splatPointValues(g, P, values);
  ASSERT_EQ(c.voxels.size(), 2u);
  EXPECT_EQ(c.voxels[0], g.linearIndex(1, 2, 3));
  EXPECT_EQ(c.voxels[1], g.linearIndex(2, 2, 3));
  EXPECT_NEAR(c.values(0, 0), (0.75 * 1 + 0.25 * 3) / 1.0, 1e-12);
  EXPECT_NEAR(c.values(1, 0), (0.25 * 1 + 0.75 * 3) / 1.0, 1e-12);
  // A point amid eight voxel centres fixes all eight with its value.
  const VoxelConstraints eight = splatPointValues(g, g.indexToWorld(Eigen::Vector3d(3.5, 1.5, 0.5)).transpose(),
                                                  Eigen::MatrixXd::Constant(1, 1, 9.0));
  ASSERT_EQ(eight.voxels.size(), 8u);
  for (Eigen::Index r = 0; r < 8; ++r) EXPECT_NEAR(eight.values(r, 0), 9.0, 1e-12);
}

TEST(PointConstraints, PointsOutsideTheGridAndMismatchesAreRefused) {
  const GridGeometry g = smallGrid();
  const MatrixX3d outside = g.indexToWorld(Eigen::Vector3d(5.2, 1, 1)).transpose();
  EXPECT_THROW(splatPointValues(g, outside, Eigen::MatrixXd::Zero(1, 3)), BadInput);
  const MatrixX3d inside = g.indexToWorld(Eigen::Vector3d(5, 4, 3)).transpose();  // the last voxel centre
  EXPECT_EQ(splatPointValues(g, inside, Eigen::MatrixXd::Zero(1, 3)).voxels.size(), 1u);
  EXPECT_THROW(splatPointValues(g, inside, Eigen::MatrixXd::Zero(2, 3)), BadInput);
  Grid<double> field(g, 0.0);
  EXPECT_THROW(writeConstraintValues(splatPointValues(g, inside, Eigen::MatrixXd::Zero(1, 3)), 3, field), UsageError);
}

// The whole path of Dicko et al. 2013, §7: an affine displacement known only at points on a sphere (a "skin")
// is splatted onto the grid and interpolated; inside, the field is the affine map up to the splat's
// O(h |∇d|) error at the shell (a harmonic function keeps its extremes on the boundary).
TEST(PointConstraints, AffineDisplacementOfASphereIsInterpolatedInside) {
  GridGeometry g;
  g.size = Eigen::Vector3i(36, 36, 30);
  g.spacing = Eigen::Vector3d(1, 1, 1.25);
  const Eigen::Vector3d centre = g.indexToWorld((g.size.cast<double>().array() - 1).matrix() / 2);
  const double radius = 14;
  Eigen::Matrix3d A;
  A << 0.1, 0.02, 0, -0.05, 0.08, 0.03, 0, 0.01, -0.06;
  const Eigen::Vector3d t(1, -2, 0.5);
  auto displacement = [&](const Eigen::Vector3d& x) { Eigen::Vector3d d = A * (x - centre) + t; return d; };
  // The sphere sampled more densely than the grid (about 0.5 mm apart).
  const int rings = 90, perRing = 180;
  MatrixX3d P(rings * perRing, 3);
  Eigen::MatrixXd D(P.rows(), 3);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < perRing; ++s) {
      const double theta = M_PI * (r + 0.5) / rings, phi = 2 * M_PI * s / perRing;
      const Eigen::Vector3d x = centre + radius * Eigen::Vector3d(std::sin(theta) * std::cos(phi),
                                                                  std::sin(theta) * std::sin(phi), std::cos(theta));
      P.row(r * perRing + s) = x.transpose();
      D.row(r * perRing + s) = displacement(x).transpose();
    }
  const VoxelConstraints c = splatPointValues(g, P, D);
  std::vector<CellRole> roles(g.voxelCount(), CellRole::Excluded);
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i)
        if ((g.indexToWorld(Eigen::Vector3d(i, j, k)) - centre).norm() < radius) roles[g.linearIndex(i, j, k)] = CellRole::Free;
  fixConstrainedVoxels(c, roles);
  LaplaceInterpolator interpolator(g, roles);
  const double tolerance = A.norm() * g.spacing.norm();  // the splat's averaging over one voxel
  for (int a = 0; a < 3; ++a) {
    Grid<double> field(g, 0.0);
    writeConstraintValues(c, a, field);
    interpolator.solve(field);
    double worst = 0;
    for (int k = 0; k < g.size.z(); ++k)
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i)
          if (roles[g.linearIndex(i, j, k)] == CellRole::Free)
            worst = std::max(worst, std::abs(field.at(i, j, k) - displacement(g.indexToWorld(Eigen::Vector3d(i, j, k)))[a]));
    EXPECT_LT(worst, tolerance) << "component " << a;
    EXPECT_GT(worst, 0.0);  // the splat is an average, not exact: the test sees real interpolation
  }
}
