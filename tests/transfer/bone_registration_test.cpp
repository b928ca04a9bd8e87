// Bone registration (Dicko et al. 2013, §8): affine, sagittally symmetric and long-bone least-squares maps.
#include "vesalius/transfer/bone_registration.h"

#include "vesalius/core/error.h"
#include "vesalius/transfer/anatomy_checks.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

MatrixX3d randomPoints(int n, unsigned seed, double extent = 50) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-extent, extent);
  MatrixX3d P(n, 3);
  for (int r = 0; r < n; ++r) P.row(r) << u(rng), u(rng), u(rng);
  return P;
}

MatrixX3d mirror(const MatrixX3d& P, const Plane& plane) {
  const Eigen::Vector3d n = plane.normal.normalized();
  const Eigen::VectorXd side = (P.rowwise() - plane.point.transpose()) * n;
  return P - 2.0 * side * n.transpose();
}

Plane plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) { return {point, normal.normalized()}; }

// A shaft 200 mm long along z, 8 mm in radius, its centre line bowed 20 mm towards x at mid-length.
MatrixX3d bowedShaft() {
  MatrixX3d P(81 * 24, 3);
  for (int k = 0; k <= 80; ++k)
    for (int j = 0; j < 24; ++j) {
      const double z = -100 + 2.5 * k, angle = 2 * M_PI * j / 24;
      P.row(24 * k + j) << 20 * (1 - z * z / 1e4) + 8 * std::cos(angle), 8 * std::sin(angle), z;
    }
  return P;
}

// A turn and shift after scaling by `along` on z and `across` on x and y.
AffineMap limbMap(double along, double across) {
  AffineMap map;
  map.A = Eigen::AngleAxisd(0.6, Eigen::Vector3d(2, -1, 1).normalized()).toRotationMatrix() *
          Eigen::Vector3d(across, across, along).asDiagonal();
  map.t << 12, -30, 45;
  return map;
}

}  // namespace

TEST(BoneRegistration, AffineFitRecoversAKnownMap) {
  const MatrixX3d P = randomPoints(200, 1);
  AffineMap truth;
  truth.A << 1.1, 0.05, -0.02, 0.03, 0.9, 0.1, -0.04, 0.02, 1.2;
  truth.t << 5, -3, 12;
  const AffineMap fit = fitAffineMap(P, truth.apply(P));
  EXPECT_LT((fit.A - truth.A).norm(), 1e-5);
  EXPECT_LT((fit.t - truth.t).norm(), 1e-4);
}

TEST(BoneRegistration, SymmetricFitCommutesWithTheMirrors) {
  const Plane reference = plane({3, 0, 0}, {1, 0.1, 0});
  const Plane target = plane({-10, 4, 2}, {0.95, -0.2, 0.1});
  const MatrixX3d P = randomPoints(300, 2);
  // Attractors that are not symmetric at all: a general affine map plus noise.
  AffineMap general;
  general.A << 1.2, 0.3, 0.1, -0.2, 0.8, 0.05, 0.1, 0.1, 1.1;
  general.t << -4, 7, 1;
  MatrixX3d Q = general.apply(P) + 0.5 * randomPoints(300, 3, 1.0);
  const AffineMap fit = fitSymmetricAffineMap(P, Q, reference, target);
  const MatrixX3d X = randomPoints(50, 4);
  // S' T = T S on any point: the image of a mirrored point is the mirrored image.
  EXPECT_LT((mirror(fit.apply(X), target) - fit.apply(mirror(X, reference))).cwiseAbs().maxCoeff(), 1e-9);
  // The reference plane's points land on the target plane.
  const Eigen::Vector3d u = reference.normal.cross(Eigen::Vector3d::UnitZ()).normalized();
  for (double s : {-40.0, 0.0, 25.0})
    EXPECT_NEAR(target.normal.dot(fit.apply(Eigen::Vector3d(reference.point + s * u)) - target.point), 0.0, 1e-9);
}

TEST(BoneRegistration, SymmetricFitRecoversASymmetricMap) {
  const Plane reference = plane({0, 0, 0}, {1, 0, 0});
  const Plane target = plane({6, 0, 0}, {1, 0, 0});
  const MatrixX3d P = randomPoints(200, 5);
  AffineMap truth;  // x' = 1.1 x + 6 (about x = 6); in-plane: a general 2-D affine map
  truth.A << 1.1, 0, 0, 0, 0.9, 0.2, 0, -0.1, 1.05;
  truth.t << 6, 3, -2;
  const AffineMap fit = fitSymmetricAffineMap(P, truth.apply(P), reference, target);
  EXPECT_LT((fit.A - truth.A).norm(), 1e-5);
  EXPECT_LT((fit.t - truth.t).norm(), 1e-4);
}

TEST(BoneRegistration, FlatBoneGetsTheUniformScaleAcrossItsPlane) {
  MatrixX3d P = randomPoints(100, 6);
  P.col(2).setZero();  // a flat bone in z = 0: A's third column is not determined by the points
  AffineMap truth;
  truth.A = 2.0 * Eigen::Matrix3d::Identity();
  const AffineMap fit = fitAffineMap(P, truth.apply(P));
  EXPECT_TRUE(fit.A.allFinite());
  EXPECT_NEAR(fit.A(2, 2), 2.0, 1e-6);
  EXPECT_LT((fit.apply(P) - truth.apply(P)).cwiseAbs().maxCoeff(), 1e-4);
}

// A thinner limb: the bone 10 % longer and 20 % more slender, turned; the long bone's map recovers it.
TEST(BoneRegistration, LongBoneFitRecoversASlenderScaling) {
  const MatrixX3d P = bowedShaft();
  const AffineMap truth = limbMap(1.1, 0.8);
  const AffineMap fit = fitLongBoneMap(P, truth.apply(P));
  EXPECT_LT((fit.A - truth.A).norm(), 1e-8);
  EXPECT_LT((fit.t - truth.t).norm(), 1e-6);
}

// A muscular limb: the interpolation widens the shaft 1.6-fold across and stretches it 1.2-fold along.
// The affine fit takes the widening in and the bow grows by 1.6 / 1.2 relative to the length (rule R1's
// centre line 3.9 % -> 5.2 %); the long bone's map keeps one scale, about the length's, and the bow.
TEST(BoneRegistration, LongBoneFitDoesNotTakeInTheMuscle) {
  const MatrixX3d P = bowedShaft(), Q = limbMap(1.2, 1.6).apply(P);
  const double reference = centreLineDeviation(P, P);
  EXPECT_NEAR(reference, 0.039, 0.002);
  EXPECT_NEAR(centreLineDeviation(P, fitAffineMap(P, Q).apply(P)), reference * 1.6 / 1.2, 1e-5);  // the ridge: 1e-6
  const AffineMap fit = fitLongBoneMap(P, Q);
  EXPECT_NEAR(centreLineDeviation(P, fit.apply(P)), reference, 1e-9);
  const Eigen::Vector3d scales = Eigen::JacobiSVD<Eigen::Matrix3d>(fit.A).singularValues();
  EXPECT_NEAR(scales.maxCoeff(), scales.minCoeff(), 1e-9);
  EXPECT_NEAR(scales.mean(), 1.2, 0.02);
}

TEST(BoneRegistration, MapPlaneCarriesThePlane) {
  AffineMap map;
  map.A << 2, 0, 0, 0, 1, 0, 0, 0, 1;
  map.A = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix() * map.A;
  map.t << 1, 2, 3;
  const Plane p = mapPlane(map, plane({5, 0, 0}, {1, 0, 0}));
  EXPECT_LT((p.point - map.apply(Eigen::Vector3d(5, 0, 0))).norm(), 1e-12);
  // Points of the old plane stay on the new one.
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(5, 10, 0), Eigen::Vector3d(5, -3, 7)})
    EXPECT_NEAR(p.normal.dot(map.apply(q) - p.point), 0.0, 1e-9);
}

TEST(BoneRegistration, AWeightCountsAsTheRowRepeated) {
  // Weight 3 on the first 20 points gives the map fitted with those points three times over, for the
  // free, the symmetric and the long bone's fit, though the attractors fit no map.
  const MatrixX3d P = randomPoints(100, 8), Q = 1.2 * P + 3.0 * randomPoints(100, 9, 1.0);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(100);
  weights.head(20).setConstant(3);
  MatrixX3d repeatedP(140, 3), repeatedQ(140, 3);
  repeatedP << P, P.topRows(20), P.topRows(20);
  repeatedQ << Q, Q.topRows(20), Q.topRows(20);
  const AffineMap weighted = fitAffineMap(P, Q, weights), repeated = fitAffineMap(repeatedP, repeatedQ);
  EXPECT_LT((weighted.A - repeated.A).norm(), 1e-9);
  EXPECT_LT((weighted.t - repeated.t).norm(), 1e-9);
  EXPECT_GT((weighted.A - fitAffineMap(P, Q).A).norm(), 1e-4);
  const Plane reference = plane({3, 0, 0}, {1, 0.1, 0}), target = plane({-10, 4, 2}, {0.95, -0.2, 0.1});
  const AffineMap symmetricWeighted = fitSymmetricAffineMap(P, Q, weights, reference, target);
  const AffineMap symmetricRepeated = fitSymmetricAffineMap(repeatedP, repeatedQ, reference, target);
  EXPECT_LT((symmetricWeighted.A - symmetricRepeated.A).norm(), 1e-9);
  EXPECT_LT((symmetricWeighted.t - symmetricRepeated.t).norm(), 1e-9);
  EXPECT_LT((fitLongBoneMap(P, Q, weights).A - fitLongBoneMap(repeatedP, repeatedQ).A).norm(), 1e-9);
}

TEST(BoneRegistration, BadInputIsRefused) {
  const MatrixX3d P = randomPoints(10, 7);
  EXPECT_THROW(fitAffineMap(P, P.topRows(9)), BadInput);
  EXPECT_THROW(fitAffineMap(P.topRows(3), P.topRows(3)), BadInput);
  MatrixX3d Q = P;
  Q(4, 1) = std::nan("");
  EXPECT_THROW(fitAffineMap(P, Q), BadInput);
  const MatrixX3d same = MatrixX3d::Constant(10, 3, 1.0);
  EXPECT_THROW(fitAffineMap(same, same), BadInput);
  EXPECT_THROW(fitLongBoneMap(same, same), BadInput);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(10);
  EXPECT_THROW(fitAffineMap(P, P, weights.head(9)), BadInput);
  weights[2] = 0;
  EXPECT_THROW(fitAffineMap(P, P, weights), BadInput);
}
