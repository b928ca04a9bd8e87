// The smallest similarity change that moves bones inside their skin (bones_inside_skin.h), on a sphere of
// radius 100 mm as the skin, whose signed distance is known exactly.
#include "vesalius/transfer/bones_inside_skin.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

namespace vesalius::transfer {
namespace {

constexpr double kRadius = 100.0;

SkinDistances sphereDistances(const MatrixX3d& P) {
  SkinDistances d{P.rowwise().norm().array() - kRadius, P.rowwise().normalized()};
  return d;
}

// A bar along `axis` from `from`, `length` mm long and 10 mm thick: a long bone's vertices.
MatrixX3d bar(const Eigen::Vector3d& from, const Eigen::Vector3d& axis, double length) {
  const Eigen::Vector3d a = axis.normalized(), u = a.unitOrthogonal(), v = a.cross(u);
  MatrixX3d V(11 * 8, 3);
  for (int i = 0; i <= 10; ++i)
    for (int k = 0; k < 8; ++k) {
      const double angle = 2 * M_PI * k / 8;
      V.row(i * 8 + k) = (from + length * i / 10.0 * a + 5.0 * (std::cos(angle) * u + std::sin(angle) * v)).transpose();
    }
  return V;
}

double deepest(const MatrixX3d& V) { return sphereDistances(V).distance.maxCoeff(); }

TEST(BonesInsideSkin, ABoneWellInsideStaysWhereItIs) {
  const MatrixX3d V = bar(Eigen::Vector3d(-20, 0, 0), Eigen::Vector3d::UnitX(), 40);
  const InsideSkinCorrection c = correctionIntoSkin(V, MatrixX3d(0, 3), sphereDistances, nullptr);
  EXPECT_EQ(c.outsideBefore, 0);
  EXPECT_EQ(c.outsideAfter, 0);
  EXPECT_LT((c.change.apply(V) - V).cwiseAbs().maxCoeff(), 1e-12);
}

// A bar poking 8 mm out along +S: it mostly moves in rather than shrinking (a scale costs 25 times more),
// until every vertex is about the margin inside.
TEST(BonesInsideSkin, ABonePokingOutMovesInByWhatItPokes) {
  const MatrixX3d V = bar(Eigen::Vector3d(0, 0, 48), Eigen::Vector3d::UnitZ(), 60);  // tip at 108 (+5 mm thick)
  ASSERT_GT(deepest(V), 7.0);
  const InsideSkinCorrection c = correctionIntoSkin(V, MatrixX3d(0, 3), sphereDistances, nullptr);
  EXPECT_EQ(c.outsideBefore, 16);  // the rings at 108 and 102 mm
  EXPECT_EQ(c.outsideAfter, 0);
  const MatrixX3d moved = c.change.apply(V);
  std::printf("deepest %.2f mm, scale %.4f, shift %.2f mm\n", deepest(moved), c.change.scale,
              (moved.colwise().mean() - V.colwise().mean()).norm());
  EXPECT_LT(deepest(moved), -1.0);  // the margin is 1.5 mm; the hinge's weight on the change leaves a little
  EXPECT_GT(deepest(moved), -2.5);
  EXPECT_GT(c.change.scale, 0.95);  // measured 0.973: the tip ring moves 0.8 mm by it, 8.7 by the shift
  const Eigen::Vector3d shift = moved.colwise().mean() - V.colwise().mean();
  EXPECT_LT(shift.z(), -7.0);
  EXPECT_LT(shift.head<2>().norm(), 1.0);
}

// An anchor at the bar's inner end (its joint): the bar turns about it instead of sliding off it.
TEST(BonesInsideSkin, AnAnchoredBoneTurnsAboutItsJoint) {
  const Eigen::Vector3d joint(0, 0, 40), axis = Eigen::Vector3d(0.3, 0, 1).normalized();
  const MatrixX3d V = bar(joint, axis, 65);
  ASSERT_GT(deepest(V), 3.0);
  const MatrixX3d anchors = joint.transpose();
  const InsideSkinCorrection free = correctionIntoSkin(V, MatrixX3d(0, 3), sphereDistances, nullptr);
  const InsideSkinCorrection anchored = correctionIntoSkin(V, anchors, sphereDistances, nullptr);
  EXPECT_EQ(anchored.outsideAfter, 0);
  const double freeJoint = (free.change.apply(joint) - joint).norm();
  const double anchoredJoint = (anchored.change.apply(joint) - joint).norm();
  std::printf("joint moved %.2f mm free, %.2f mm anchored; turn %.1f deg\n", freeJoint, anchoredJoint,
              Eigen::AngleAxisd(anchored.change.rotation).angle() * 180 / M_PI);
  EXPECT_LT(anchoredJoint, 0.5 * freeJoint);
}

// A symmetric group (a bar across the sagittal plane x = 3, poking out posteriorly and to the left) moves
// only in the plane and turns only about its normal: its mirror image stays its own.
TEST(BonesInsideSkin, ASymmetricGroupStaysSymmetric) {
  const Plane sagittal{Eigen::Vector3d(3, 0, 0), Eigen::Vector3d::UnitX()};
  const MatrixX3d V = bar(Eigen::Vector3d(-37, 95, 0), Eigen::Vector3d::UnitX(), 80);  // x from -37 to 43
  ASSERT_GT(deepest(V), 0.0);
  const InsideSkinCorrection c = correctionIntoSkin(V, MatrixX3d(0, 3), sphereDistances, &sagittal);
  EXPECT_EQ(c.outsideAfter, 0);
  const Eigen::AngleAxisd turn(c.change.rotation);
  EXPECT_TRUE(turn.angle() < 1e-12 || std::abs(std::abs(turn.axis().x()) - 1.0) < 1e-9);
  // The plane's points stay on it, so the change commutes with the mirror.
  const Eigen::Vector3d onPlane(3, 10, 20);
  EXPECT_NEAR(c.change.apply(onPlane).x(), 3.0, 1e-9);
  EXPECT_NEAR(c.change.apply(Eigen::Vector3d(3, -50, 7)).x(), 3.0, 1e-9);
}

// A bone larger than the skin: the caps hold and it stays partly outside.
TEST(BonesInsideSkin, TheCapsHoldWhereNoSimilarityFits) {
  const MatrixX3d V = bar(Eigen::Vector3d(-150, 0, 0), Eigen::Vector3d::UnitX(), 300);
  InsideSkinOptions o;
  o.minScale = 0.9;
  o.maxShiftMm = 5;
  o.maxTurnDegrees = 10;
  const InsideSkinCorrection c = correctionIntoSkin(V, MatrixX3d(0, 3), sphereDistances, nullptr, o);
  EXPECT_GT(c.outsideAfter, 0);
  EXPECT_LT(deepest(c.change.apply(V)), deepest(V) - 10.0);  // 150 mm ends: the scale's cap alone takes 15 off
  EXPECT_GE(c.change.scale, 0.9 - 1e-12);
  EXPECT_LE(Eigen::AngleAxisd(c.change.rotation).angle(), 10 * M_PI / 180 + 1e-9);
  const Eigen::Vector3d centroid = V.colwise().mean().transpose();
  EXPECT_LE((c.change.apply(centroid) - centroid).norm(), 5.0 + 1e-9);
}

TEST(BonesInsideSkin, BadInput) {
  EXPECT_THROW(correctionIntoSkin(MatrixX3d(0, 3), MatrixX3d(0, 3), sphereDistances, nullptr), UsageError);
  InsideSkinOptions o;
  o.minScale = 0;
  EXPECT_THROW(correctionIntoSkin(bar(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 10), MatrixX3d(0, 3),
                                  sphereDistances, nullptr, o),
               UsageError);
}

}  // namespace
}  // namespace vesalius::transfer
