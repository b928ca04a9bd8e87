// Tissue points carried by the tet mesh (Sujar et al. 2018, §3.4-3.5): embedding, barycentric transfer and the
// per-tet affine maps agree, and reproduce affine deformations exactly, inside and outside the mesh.
#include "vesalius/posing/tet_affine_maps.h"
#include "vesalius/core/tet_embedding.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"

#include "test_tets.h"

#include <gtest/gtest.h>

#include <random>

using namespace vesalius;

namespace {

MatrixX3d randomPoints(int n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng), u(rng);
  return P;
}

Eigen::Affine3d someAffineMap() {
  Eigen::Affine3d A = Eigen::Affine3d::Identity();
  A.linear() << 1.3, 0.2, -0.1, 0.05, 0.8, 0.3, -0.2, 0.1, 1.1;
  A.translation() << 4, -2, 9;
  return A;
}

MatrixX3d transformed(const Eigen::Affine3d& A, const MatrixX3d& P) {
  return (P * A.linear().transpose()).rowwise() + A.translation().transpose();
}

}  // namespace

TEST(TetEmbedding, ReproducesAnAffineDeformationInsideAndOutside) {
  const TetMesh box = test::boxTets(3, 3, 3, 10.0);
  const Eigen::Affine3d A = someAffineMap();
  for (const auto& [lo, hi] : {std::pair{0.0, 30.0}, std::pair{-5.0, 35.0}}) {
    const MatrixX3d P = randomPoints(500, lo, hi, 7);
    const TetEmbedding e = embedInTets(box.V, box.T, P);
    const double error = (e.apply(transformed(A, box.V)) - transformed(A, P)).cwiseAbs().maxCoeff();
    EXPECT_LT(error, 1e-11) << "points in [" << lo << ", " << hi << "]^3";
  }
}

TEST(TetEmbedding, PointsInsideGetTheirContainingTet) {
  const TetMesh box = test::boxTets(3, 3, 3, 10.0);
  const MatrixX3d P = randomPoints(500, 0.0, 30.0, 11);
  const TetEmbedding e = embedInTets(box.V, box.T, P);
  EXPECT_GE(e.barycentric.minCoeff(), -1e-12);
  EXPECT_LT((e.barycentric.rowwise().sum().array() - 1.0).abs().maxCoeff(), 1e-12);
  for (Eigen::Index p = 0; p < P.rows(); ++p) ASSERT_EQ(e.corners.row(p), box.T.row(e.tet[p]));
}

// Inside, the locator's weights are kept; outside, the nearest tet's unclamped weights are computed: both
// must be exactly barycentric(tet, p), as when the embedding computed them all again.
TEST(TetEmbedding, WeightsAreTheBarycentricCoordinatesInTheirTet) {
  const TetMesh box = test::boxTets(3, 3, 3, 10.0);
  const MatrixX3d P = randomPoints(500, -5.0, 35.0, 13);
  const TetEmbedding e = embedInTets(box.V, box.T, P);
  const TetLocator locator(box.V, box.T);
  int outside = 0;
  for (Eigen::Index p = 0; p < P.rows(); ++p) {
    ASSERT_EQ(e.barycentric.row(p).transpose(), locator.barycentric(e.tet[p], P.row(p).transpose())) << p;
    outside += e.barycentric.row(p).minCoeff() < -1e-9;
  }
  EXPECT_GT(outside, 100);  // 1 - (3 / 4)^3 of the points lie outside the box
  MatrixX3d carried = MatrixX3d::Zero(2, 3);  // reused buffer of another size
  e.apply(box.V, carried);
  EXPECT_EQ(carried, e.apply(box.V));
  EXPECT_LT((carried - P).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_THROW(e.apply(box.V.topRows(20), carried), UsageError);
}

TEST(TetAffineMaps, AgreeWithTheEmbeddingUnderANonlinearDeformation) {
  const TetMesh box = test::boxTets(3, 3, 3, 10.0);
  MatrixX3d posed = box.V;
  for (Eigen::Index v = 0; v < posed.rows(); ++v)  // a bend: not affine, so every tet has its own map
    posed.row(v) << box.V(v, 0) + 0.01 * box.V(v, 1) * box.V(v, 1), box.V(v, 1) + 3.0 * std::sin(box.V(v, 0) / 9.0),
        box.V(v, 2);
  const MatrixX3d P = randomPoints(300, 0.0, 30.0, 3);
  const TetEmbedding e = embedInTets(box.V, box.T, P);
  const std::vector<Eigen::Affine3d> maps = posing::tetAffineMaps(box.V, box.T, posed);
  const MatrixX3d carried = e.apply(posed);
  for (Eigen::Index p = 0; p < P.rows(); ++p)
    EXPECT_LT((maps[std::size_t(e.tet[p])] * Eigen::Vector3d(P.row(p)) - carried.row(p).transpose()).norm(), 1e-11);
  const Eigen::Affine3d A = someAffineMap();
  for (const Eigen::Affine3d& map : posing::tetAffineMaps(box.V, box.T, transformed(A, box.V)))
    ASSERT_LT((map.matrix() - A.matrix()).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(TetAffineMaps, RefuseAFlatTetAndMismatchedSizes) {
  TetMesh box = test::boxTets(1, 1, 1);
  EXPECT_THROW(posing::tetAffineMaps(box.V, box.T, box.V.topRows(3)), UsageError);
  box.V.row(box.T(0, 3)) = box.V.row(box.T(0, 0));
  EXPECT_THROW(posing::tetAffineMaps(box.V, box.T, box.V), BadInput);
}
