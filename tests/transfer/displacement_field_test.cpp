// Displacement fields from scattered boundary displacements (Dicko et al. 2013, §7).
#include "vesalius/transfer/displacement_field.h"

#include "vesalius/meshing/mesh_volume.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

struct Body {
  TriMesh skin;
  Grid<std::uint8_t> inside;
};

Body sphereBody(double radius, double voxel) {
  Body body;
  body.skin = test::sphere(5, radius);  // 8192 triangles, vertices about 2 mm apart at radius 40
  meshing::CoveringGridOptions grid;
  grid.voxelSizeMm = voxel;
  grid.marginMm = 2 * voxel;
  body.inside = meshing::meshInsideMask(body.skin, meshing::coveringGrid({&body.skin}, grid));
  return body;
}

// The centres of the inside voxels that touch an outside voxel: points where the Nearest splat fixes
// exactly the given value, so that the fields below are exact up to the solver's tolerance.
MatrixX3d boundaryVoxelCentres(const Grid<std::uint8_t>& inside) {
  const GridGeometry& g = inside.geometry;
  std::vector<Eigen::Vector3d> centres;
  for (int k = 1; k + 1 < g.size.z(); ++k)
    for (int j = 1; j + 1 < g.size.y(); ++j)
      for (int i = 1; i + 1 < g.size.x(); ++i)
        if (inside.at(i, j, k) && !(inside.at(i - 1, j, k) && inside.at(i + 1, j, k) && inside.at(i, j - 1, k) &&
                                    inside.at(i, j + 1, k) && inside.at(i, j, k - 1) && inside.at(i, j, k + 1)))
          centres.push_back(g.indexToWorld(Eigen::Vector3d(i, j, k)));
  MatrixX3d P(Eigen::Index(centres.size()), 3);
  for (std::size_t r = 0; r < centres.size(); ++r) P.row(Eigen::Index(r)) = centres[r].transpose();
  return P;
}

MatrixX3d affineDisplacement(const MatrixX3d& P, const Eigen::Matrix3d& M, const Eigen::Vector3d& c) {
  return (P * M.transpose()).rowwise() + c.transpose();
}

const Eigen::Matrix3d kM = (Eigen::Matrix3d() << 0.2, 0.05, 0, -0.03, -0.1, 0.04, 0.02, 0, 0.15).finished();
const Eigen::Vector3d kC(3, -2, 5);

}  // namespace

TEST(DisplacementField, AnAffineDisplacementIsExactInsideAndItsJacobianToo) {
  const Body body = sphereBody(40, 2);
  const MatrixX3d P = boundaryVoxelCentres(body.inside);
  DisplacementFieldOptions options;
  options.splat.method = SplatMethod::Nearest;
  const DisplacementField field = interpolateDisplacements(body.inside, P, affineDisplacement(P, kM, kC), options);
  // Linear functions are harmonic: the interior is the affine map itself.
  const MatrixX3d inner = test::sphere(3, 25).V;
  EXPECT_LT((field.displace(inner) - inner - affineDisplacement(inner, kM, kC)).cwiseAbs().maxCoeff(), 1e-5);
  const JacobianSummary jacobian = jacobianDeterminant(field);
  EXPECT_GT(jacobian.measuredCells, 20000);
  EXPECT_NEAR(jacobian.minimum, (Eigen::Matrix3d::Identity() + kM).determinant(), 1e-6);
  EXPECT_EQ(jacobian.nonPositiveCells, 0);
}

TEST(DisplacementField, SkinVerticesGiveTheFieldToFirstOrderInTheSpacing) {
  // The trilinear splat fixes each shell voxel to a weighted mean of nearby vertex values, i.e. the
  // field at a point up to a voxel from the voxel centre (point_constraints.h): an error of order
  // h |∇u| = 2 mm x 0.27 here, not round-off.
  const Body body = sphereBody(40, 2);
  const DisplacementField field =
      interpolateDisplacements(body.inside, body.skin.V, affineDisplacement(body.skin.V, kM, kC));
  const MatrixX3d inner = test::sphere(3, 25).V;
  EXPECT_LT((field.displace(inner) - inner - affineDisplacement(inner, kM, kC)).cwiseAbs().maxCoeff(), 0.3);
  EXPECT_LT((field.displace(body.skin.V) - body.skin.V - affineDisplacement(body.skin.V, kM, kC)).cwiseAbs().maxCoeff(),
            0.1);
}

TEST(DisplacementField, AnInvertingDisplacementShowsAsFolds) {
  const Body body = sphereBody(30, 3);
  const MatrixX3d P = boundaryVoxelCentres(body.inside);
  DisplacementFieldOptions options;
  options.splat.method = SplatMethod::Nearest;
  // x ↦ −x: det(I + ∇u) = −1 everywhere.
  const JacobianSummary jacobian = jacobianDeterminant(interpolateDisplacements(body.inside, P, -2.0 * P, options));
  EXPECT_NEAR(jacobian.minimum, -1.0, 1e-6);
  EXPECT_EQ(jacobian.nonPositiveCells, jacobian.measuredCells);
  EXPECT_GT(jacobian.interiorCells, 1000);
  EXPECT_LT(jacobian.interiorCells, jacobian.measuredCells);
  EXPECT_EQ(jacobian.interiorNonPositiveCells, jacobian.interiorCells);
  EXPECT_NEAR(jacobian.interiorMinimum, -1.0, 1e-6);
}

TEST(DisplacementField, ABulgeStaysHarmonicAndBounded) {
  const Body body = sphereBody(40, 2);
  // Push the upper cap outward by up to 8 mm: the interior moves less than the skin (maximum principle).
  MatrixX3d u = MatrixX3d::Zero(body.skin.V.rows(), 3);
  for (Eigen::Index r = 0; r < u.rows(); ++r) {
    const double z = body.skin.V(r, 2) / 40;
    if (z > 0) u(r, 2) = 8 * z * z;
  }
  const DisplacementField field = interpolateDisplacements(body.inside, body.skin.V, u);
  const MatrixX3d inner = test::sphere(3, 20).V;
  const MatrixX3d moved = field.displace(inner) - inner;
  EXPECT_LE(moved.col(2).maxCoeff(), 8.0);
  EXPECT_GE(moved.col(2).minCoeff(), -1e-6);
  EXPECT_GT(moved.col(2).maxCoeff(), 0.5);
  EXPECT_GT(jacobianDeterminant(field).minimum, 0.5);
}

TEST(DisplacementField, SecondSolveStartsFromTheFirst) {
  const Body body = sphereBody(30, 3);
  const MatrixX3d u = 0.1 * body.skin.V;
  const DisplacementField first = interpolateDisplacements(body.inside, body.skin.V, u);
  const DisplacementField second = interpolateDisplacements(body.inside, body.skin.V, u, {}, &first);
  EXPECT_LE(second.solves[0].iterations, 1);
  EXPECT_GT(first.solves[0].iterations, 1);
}

// A bone (a sphere of radius 30 mm) inside a skin (radius 40 mm), both moved by one affine map, the bone's
// cap above z = 20 mm pushed up to 14 mm further out, through the skin: the cells between fold. Freeing
// the fixed cells at the folds (unfoldPasses) unfolds them; the field away from the cap keeps its values.
TEST(DisplacementField, FreeingTheFixedCellsAtFoldsUnfoldsThem) {
  const Body body = sphereBody(40, 2);
  const MatrixX3d bone = test::sphere(4, 30).V;
  MatrixX3d P(body.skin.V.rows() + bone.rows(), 3);
  P << body.skin.V, bone;
  MatrixX3d u = affineDisplacement(P, kM, kC);
  for (Eigen::Index r = body.skin.V.rows(); r < P.rows(); ++r)
    if (P(r, 2) > 20) u.row(r) += 1.4 * (P(r, 2) - 20) * P.row(r).normalized();
  DisplacementFieldOptions options;
  const JacobianSummary folded = jacobianDeterminant(interpolateDisplacements(body.inside, P, u, options));
  options.unfoldPasses = 40;
  const DisplacementField field = interpolateDisplacements(body.inside, P, u, options);
  const JacobianSummary unfolded = jacobianDeterminant(field);
  const auto fixedCells = std::count(field.roles.begin(), field.roles.end(), CellRole::Fixed);
  std::printf("folded cells %lld (minimum %.2f) -> %lld (minimum %.2f) in %d passes, %lld fixed cells freed, %lld kept\n",
              (long long)folded.nonPositiveCells, folded.minimum, (long long)unfolded.nonPositiveCells,
              unfolded.minimum, field.unfoldPasses, (long long)field.releasedCells, (long long)fixedCells);
  EXPECT_GT(folded.nonPositiveCells, 0);
  EXPECT_EQ(unfolded.nonPositiveCells, 0);
  EXPECT_GT(field.releasedCells, 0);
  EXPECT_LT(field.releasedCells, fixedCells / 5);
  // Below the cap the bone's and skin's cells stay fixed: the field there is the affine map to the splat's
  // first order (as SkinVerticesGiveTheFieldToFirstOrderInTheSpacing).
  std::vector<Eigen::Index> below;
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    if (P(r, 2) < 0) below.push_back(r);
  const MatrixX3d B = P(below, Eigen::all);
  EXPECT_LT((field.displace(B) - B - affineDisplacement(B, kM, kC)).cwiseAbs().maxCoeff(), 0.3);
}
