// A bone mesh bent inside its skin (bone_deformation_into_skin.h): a sphere of radius 40 mm pushed into a
// smaller closed surface whose signed distance is known exactly, and a sphere across a cavity of the skin.
#include "vesalius/transfer/bone_deformation_into_skin.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"

#include "test_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

namespace vesalius::transfer {
namespace {

// Signed distances of a skin given by its signed distance function, the outward direction by central
// differences (0.01 mm).
SkinDistanceFunction skinOf(std::function<double(const Eigen::Vector3d&)> sdf) {
  return [sdf](const MatrixX3d& P) {
    SkinDistances d{Eigen::VectorXd(P.rows()), MatrixX3d(P.rows(), 3)};
    for (Eigen::Index r = 0; r < P.rows(); ++r) {
      const Eigen::Vector3d p = P.row(r).transpose();
      d.distance[r] = sdf(p);
      Eigen::Vector3d g;
      for (int a = 0; a < 3; ++a) {
        const Eigen::Vector3d h = 0.01 * Eigen::Vector3d::Unit(a);
        g[a] = (sdf(p + h) - sdf(p - h)) / 0.02;
      }
      d.outward.row(r) = g.normalized().transpose();
    }
    return d;
  };
}

// The skin: a sphere of radius 50 mm about the origin.
double ballSkin(const Eigen::Vector3d& p) { return p.norm() - 50.0; }

// The skin with a mouth: the ball less a slot 20 mm tall (|z| < 10) reaching in from +x to x = −20 (the
// slot's signed distance as a box's, infinite along y and +x).
double mouthSkin(const Eigen::Vector3d& p) {
  const double back = -20.0 - p.x(), wall = std::abs(p.z()) - 10.0;
  const double slot = std::hypot(std::max(back, 0.0), std::max(wall, 0.0)) + std::min(std::max(back, wall), 0.0);
  return std::max(ballSkin(p), -slot);
}

// The largest difference between the displacements of two vertices that share an edge.
double largestNeighbourDifference(const TriMesh& m, const MatrixX3d& U) {
  double largest = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) largest = std::max(largest, (U.row(m.F(f, c)) - U.row(m.F(f, (c + 1) % 3))).norm());
  return largest;
}

// A ball of radius 40 about (18, 0, 0) pokes 8 mm out of the 50 mm skin on the +x side. Bent: every
// vertex inside by about the margin, the bend smooth, the far side (30 mm and more inside) hardly moved.
TEST(BoneDeformationIntoSkin, ABallPokingOutIsBentInsideSmoothly) {
  const TriMesh bone = test::sphere(4, 40.0, Eigen::Vector3d(18, 0, 0));  // 1,026 vertices, edges about 4 mm
  const SkinDistanceFunction skin = skinOf(ballSkin);
  const IntoSkinDeformation bend = deformationIntoSkin(bone, skin);
  const SkinDistances before = skin(bone.V), after = skin(bone.V + bend.displacement);
  EXPECT_GT(bend.outsideBefore, 100);
  EXPECT_EQ(bend.outsideAfter, 0);
  const double deepest = after.distance.maxCoeff();
  const double smoothness = largestNeighbourDifference(bone, bend.displacement);
  double farMove = 0;
  for (Eigen::Index i = 0; i < bone.V.rows(); ++i)
    if (before.distance[i] < -30.0) farMove = std::max(farMove, bend.displacement.row(i).norm());
  const double volumeChange = enclosedVolume(bone.V + bend.displacement, bone.F) / enclosedVolume(bone.V, bone.F) - 1;
  std::printf("%ld outside before, %d steps; shallowest %.2f mm, largest move %.2f mm, neighbours differ by "
              "%.2f mm at most, far side moved %.2f mm at most, volume %+.1f %%\n",
              bend.outsideBefore, bend.steps, deepest, bend.displacement.rowwise().norm().maxCoeff(), smoothness,
              farMove, 100 * volumeChange);
  EXPECT_LT(deepest, -0.5);  // the margin is 1.5 mm; the membrane's pull leaves a little
  EXPECT_LT(bend.displacement.rowwise().norm().maxCoeff(), 12.0);  // 8 mm out, + the margin, + the spread
  EXPECT_LT(smoothness, 1.5);  // edges about 3.9 mm long
  EXPECT_LT(farMove, 0.1);
  EXPECT_LT(volumeChange, 0.0);
}

// A ball already inside is not touched.
TEST(BoneDeformationIntoSkin, ABallInsideStaysWhereItIs) {
  const TriMesh bone = test::sphere(3, 20.0, Eigen::Vector3d(5, 0, 0));
  const IntoSkinDeformation bend = deformationIntoSkin(bone, skinOf(ballSkin));
  EXPECT_EQ(bend.outsideBefore, 0);
  EXPECT_EQ(bend.steps, 0);
  EXPECT_EQ(bend.displacement.cwiseAbs().maxCoeff(), 0.0);
}

// A ball across the mouth (radius 15 about (0, 0, 12), z from −3 to 27, its lower part in the slot): the closest ways out
// send the vertices near z = 0 down and those above up, tearing the ball across the slot; with the way out
// upwards preferred, every vertex in the slot leaves it upwards, and the ball is not torn.
TEST(BoneDeformationIntoSkin, APreferredWayOutKeepsABoneWholeAcrossACavity) {
  const TriMesh bone = test::sphere(4, 15.0, Eigen::Vector3d(0, 0, 12));
  const SkinDistanceFunction skin = skinOf(mouthSkin);
  IntoSkinDeformationOptions up;
  up.preferredDirection = Eigen::Vector3d::UnitZ();
  const IntoSkinDeformation closest = deformationIntoSkin(bone, skin), upwards = deformationIntoSkin(bone, skin, up);
  const MatrixX3d torn = bone.V + closest.displacement, whole = bone.V + upwards.displacement;
  std::printf("closest ways: %ld -> %ld outside, lowest vertex at z %.1f, neighbours differ by %.1f mm; upwards: "
              "%ld -> %ld, lowest at z %.1f, neighbours differ by %.1f mm\n",
              closest.outsideBefore, closest.outsideAfter, torn.col(2).minCoeff(),
              largestNeighbourDifference(bone, closest.displacement), upwards.outsideBefore, upwards.outsideAfter,
              whole.col(2).minCoeff(), largestNeighbourDifference(bone, upwards.displacement));
  EXPECT_GT(upwards.outsideBefore, 200);
  EXPECT_EQ(upwards.outsideAfter, 0);
  EXPECT_LT(torn.col(2).minCoeff(), -10.0);      // some of it pushed out under the slot
  EXPECT_GT(whole.col(2).minCoeff(), 10.0);      // all of it above the slot
  EXPECT_LT(largestNeighbourDifference(bone, upwards.displacement),
            0.5 * largestNeighbourDifference(bone, closest.displacement));
}

TEST(BoneDeformationIntoSkin, BadInput) {
  const SkinDistanceFunction skin = skinOf(ballSkin);
  EXPECT_THROW(deformationIntoSkin(TriMesh{}, skin), UsageError);
  IntoSkinDeformationOptions o;
  o.smoothness = 0;
  EXPECT_THROW(deformationIntoSkin(test::sphere(1, 10.0), skin, o), UsageError);
  o = {};
  o.preferredDirection = Eigen::Vector3d(std::nan(""), 0, 0);
  EXPECT_THROW(deformationIntoSkin(test::sphere(1, 10.0), skin, o), UsageError);
}

}  // namespace
}  // namespace vesalius::transfer
