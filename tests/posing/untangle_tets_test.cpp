// Local untangling of skinned tets (untangle_tets.h): the energy's gradient against finite differences, a
// vertex pushed through its neighbours inside a box and on its surface, and the four-bone bar of Sujar et al. 2018,
// Fig. 7, bent until LBS, DQS and CoR invert tets at the inside of the joint.
#include "vesalius/posing/untangle_tets.h"

#include "vesalius/core/error.h"
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/rotation_centers.h"

#include "posing_test_support.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <random>

using namespace vesalius;

namespace {

using Corners = Eigen::Matrix<double, 4, 3>;

long countBelow(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, double ratio) {
  return ((tetVolumes(posedV, T).array() / tetVolumes(restV, T).array()) < ratio).count();
}

double smallestRatio(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV) {
  return (tetVolumes(posedV, T).array() / tetVolumes(restV, T).array()).minCoeff();
}

// A box of nx × 8 × 8 unit cubes whose outer layer of vertices is bone (fixed), or only the bottom layer.
struct Box {
  int nx;
  TetMesh mesh = test::boxTets(nx, 8, 8);
  Eigen::VectorXi bone;
  int vertexAt(int i, int j, int k) const { return (k * 9 + j) * (nx + 1) + i; }
  explicit Box(bool onlyBottomFixed, int length = 8) : nx(length), bone(Eigen::VectorXi::Constant(mesh.V.rows(), -1)) {
    for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
      const Eigen::RowVector3d x = mesh.V.row(v);
      const bool outside = x.minCoeff() == 0 || x.x() == nx || x.y() == 8 || x.z() == 8;
      if (onlyBottomFixed ? x.z() == 0 : outside) bone[v] = 0;
    }
  }
};

}  // namespace

TEST(UntangleTets, TetEnergyGradientMatchesFiniteDifferences) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  Corners rest;
  rest << 0, 0, 0, 2, 0.1, 0, 0.3, 1.8, 0.2, 0.4, 0.5, 2.2;
  double worst = 0;
  for (const double epsilon : {1.0, 1e-2, 1e-6}) {
    for (int trial = 0; trial < 20; ++trial) {
      Corners posed = rest;
      for (int i = 0; i < posed.size(); ++i) posed.data()[i] += 1.2 * u(random);  // many of them inverted
      Corners gradient;
      posing::TetUntangler::tetEnergy(rest, posed, epsilon, 0.5, &gradient);
      for (int i = 0; i < posed.size(); ++i) {
        const double h = 1e-6;
        Corners plus = posed, minus = posed;
        plus.data()[i] += h;
        minus.data()[i] -= h;
        const double fd = (posing::TetUntangler::tetEnergy(rest, plus, epsilon, 0.5) -
                           posing::TetUntangler::tetEnergy(rest, minus, epsilon, 0.5)) / (2 * h);
        worst = std::max(worst, std::abs(fd - gradient.data()[i]) / std::max(1.0, std::abs(fd)));
      }
    }
  }
  std::printf("tet energy gradient against central differences: worst relative error %.2e\n", worst);
  EXPECT_LT(worst, 1e-6);
}

TEST(UntangleTets, TetEnergyIsSmallestAtARigidMotionOfTheRestTet) {
  Corners rest;
  rest << 0, 0, 0, 2, 0.1, 0, 0.3, 1.8, 0.2, 0.4, 0.5, 2.2;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  const Corners posed = (rest * R.transpose()).rowwise() + Eigen::RowVector3d(5, -3, 2);
  Corners gradient;
  const double volume = tetVolumes(rest, (MatrixX4i(1, 4) << 0, 1, 2, 3).finished())[0];
  // f = tr(JᵀJ) = 3, g = (1 + 1) / 1 = 2 at J = R (χ = D = 1 as ε → 0).
  EXPECT_NEAR(posing::TetUntangler::tetEnergy(rest, posed, 1e-10, 0.5, &gradient), volume * 2.5, 1e-12);
  EXPECT_LT(gradient.cwiseAbs().maxCoeff(), 1e-12);
}

// A vertex in the middle of the box pushed 1.6 along x, through the far faces of its tets (the box's outer
// layer is bone).
TEST(UntangleTets, RepairsAVertexPushedThroughItsNeighboursInsideABox) {
  const Box box(false);
  MatrixX3d posed = box.mesh.V;
  const int pushed = box.vertexAt(4, 4, 4);
  posed(pushed, 0) += 1.6;
  const posing::TetUntangler untangle(box.mesh.V, box.mesh.T, box.bone);
  const MatrixX3d before = posed;
  const posing::UntangleResult r = untangle(posed);
  const double back = (posed.row(pushed) - box.mesh.V.row(pushed)).norm();
  long movedOutside = 0;  // vertices beyond two rings (|offset| > 3 cells) that moved
  for (Eigen::Index v = 0; v < posed.rows(); ++v)
    if ((box.mesh.V.row(v) - box.mesh.V.row(pushed)).cwiseAbs().maxCoeff() > 3 && posed.row(v) != before.row(v))
      ++movedOutside;
  std::printf("box: %ld bad tets before, %ld after, %ld regions, %ld vertices moved, max %.3f; pushed vertex "
              "%.2e from rest; smallest ratio %.3f\n", r.badBefore, r.badAfter, r.regions, r.movedVertices,
              r.maxMove, back, smallestRatio(box.mesh.V, box.mesh.T, posed));
  EXPECT_EQ(r.badBefore, countBelow(box.mesh.V, box.mesh.T, before, 0.05));
  EXPECT_EQ(r.badBefore, 6);  // the six tets of the +x side of its star (measured)
  EXPECT_EQ(r.badAfter, 0);
  EXPECT_GE(smallestRatio(box.mesh.V, box.mesh.T, posed), 0.05);
  // Once every tet holds 0.05 of its rest volume the region is relaxed with the exact barrier; the ring
  // around it lies at rest, so the region's least energy is its rest shape: the pushed vertex goes back,
  // and no vertex moves further than it was pushed.
  EXPECT_LT(back, 1e-3);
  EXPECT_LE(r.maxMove, 1.6 + 1e-3);
  EXPECT_EQ(movedOutside, 0);
  for (Eigen::Index v = 0; v < posed.rows(); ++v) {
    if (box.bone[v] >= 0) {
      EXPECT_EQ(posed.row(v), before.row(v)) << v;
    }
  }
}

// The middle vertex of the top face pushed 1.6 down, through the tets below it; only the bottom is bone, so
// the free surface around it must make room.
TEST(UntangleTets, RepairsAVertexPushedIntoTheBoxThroughItsSurface) {
  const Box box(true);
  MatrixX3d posed = box.mesh.V;
  const int pushed = box.vertexAt(4, 4, 8);
  posed(pushed, 2) -= 1.6;
  const posing::TetUntangler untangle(box.mesh.V, box.mesh.T, box.bone);
  const posing::UntangleResult r = untangle(posed);
  std::printf("surface: %ld bad tets before, %ld after, %ld regions, %ld vertices moved, max %.3f; pushed vertex "
              "%.4f from rest; smallest ratio %.3f\n", r.badBefore, r.badAfter, r.regions, r.movedVertices,
              r.maxMove, (posed.row(pushed) - box.mesh.V.row(pushed)).norm(),
              smallestRatio(box.mesh.V, box.mesh.T, posed));
  EXPECT_EQ(r.badBefore, 6);
  EXPECT_EQ(r.badAfter, 0);
  EXPECT_GE(smallestRatio(box.mesh.V, box.mesh.T, posed), 0.05);
  // Relaxed with the exact barrier, the free surface around it at rest: back to the rest shape.
  EXPECT_LT((posed.row(pushed) - box.mesh.V.row(pushed)).norm(), 1e-3);
  EXPECT_LE(r.maxMove, 1.6 + 1e-3);
}

namespace {

struct BentBar {
  test::BoneBar bar = test::fourBoneBar();
  Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  MatrixX3d centres = posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W);
};

const BentBar& bentBar() {
  static const BentBar b;
  return b;
}

}  // namespace

TEST(UntangleTets, RepairsTheInsideOfTheBentBarForEverySkinning) {
  const BentBar& b = bentBar();
  const MatrixX3d& V = b.bar.mesh.V;
  const MatrixX4i& T = b.bar.mesh.T;
  const posing::TetUntangler untangle(V, T, b.bar.boneOfVertex);
  for (const double degrees : {100.0, 120.0, 140.0}) {
    const auto pose = test::middleJointPose(b.bar, Eigen::Vector3d::UnitY(), degrees);
    const std::pair<const char*, MatrixX3d> skinned[] = {
        {"LBS", posing::linearBlendSkinning(V, b.W, pose)},
        {"DQS", posing::dualQuaternionSkinning(V, b.W, pose)},
        {"CoR", posing::corSkinning(V, b.W, b.centres, pose)}};
    for (const auto& [name, S] : skinned) {
      MatrixX3d posed = S;
      const posing::UntangleResult r = untangle(posed);
      double boneMove = 0;
      for (Eigen::Index v = 0; v < V.rows(); ++v)
        if (b.bar.boneOfVertex[v] >= 0) boneMove = std::max(boneMove, (posed.row(v) - S.row(v)).norm());
      std::printf("bar %3.0f° %s: inverted %ld, below 0.05 %ld -> %ld (%ld regions), moved %ld max %.3f, ratio "
                  "%.3f -> %.3f, volume %+.2f %% -> %+.2f %%, %.0f ms\n",
                  degrees, name, countBelow(V, T, S, 1e-300), r.badBefore, r.badAfter, r.regions, r.movedVertices,
                  r.maxMove, smallestRatio(V, T, S), smallestRatio(V, T, posed), 100 * test::volumeChange(V, T, S),
                  100 * test::volumeChange(V, T, posed), 1000 * r.seconds);
      EXPECT_GT(r.badBefore, 200) << name << ' ' << degrees;  // measured 225-533
      EXPECT_EQ(r.badAfter, 0) << name << ' ' << degrees;
      EXPECT_GE(smallestRatio(V, T, posed), 0.05);
      EXPECT_LT(r.maxMove, 8.0);  // within the bar's thickness: the fold pushed out of the joint, not beyond
      EXPECT_EQ(boneMove, 0.0);
    }
  }
}

// Two pushed vertices far apart along a long box: two regions, solved in parallel; the same on one thread.
TEST(UntangleTets, SeparateRegionsGiveTheSameResultOnOneThread) {
  const Box box(false, 16);
  MatrixX3d skinned = box.mesh.V;
  skinned(box.vertexAt(3, 4, 4), 0) += 1.6;
  skinned(box.vertexAt(13, 4, 4), 1) -= 1.5;
  const posing::TetUntangler untangle(box.mesh.V, box.mesh.T, box.bone);
  MatrixX3d parallel = skinned, serial = skinned;
  const posing::UntangleResult r = untangle(parallel);
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    untangle(serial);
  }
  EXPECT_EQ(r.regions, 2);
  EXPECT_EQ(r.badBefore, 12);
  EXPECT_EQ(r.badAfter, 0);
  EXPECT_EQ(parallel, serial);
}

TEST(UntangleTets, BadInputAndOptionsAreRefused) {
  const Box box(false);
  posing::UntangleOptions bad;
  bad.minVolumeRatio = 0;
  EXPECT_THROW(posing::TetUntangler(box.mesh.V, box.mesh.T, box.bone, bad), UsageError);
  bad = {};
  bad.maxRings = 1;  // below rings
  EXPECT_THROW(posing::TetUntangler(box.mesh.V, box.mesh.T, box.bone, bad), UsageError);
  bad = {};
  bad.releaseRounds = -1;
  EXPECT_THROW(posing::TetUntangler(box.mesh.V, box.mesh.T, box.bone, bad), UsageError);
  test::expectBadRestRigsRefused(box.mesh, box.bone, [](const auto& V, const auto& T, const auto& bone) {
    return posing::TetUntangler(V, T, bone);
  });
  const posing::TetUntangler untangle(box.mesh.V, box.mesh.T, box.bone);
  MatrixX3d tooFew = box.mesh.V.topRows(5);
  EXPECT_THROW(untangle(tooFew), UsageError);
}

// Where every corner of a bad tet is a bone vertex (two bones meeting), nothing may move: counted, left.
TEST(UntangleTets, LeavesBadTetsWhoseCornersAreAllBone) {
  Box box(false);
  box.bone.setZero();
  MatrixX3d posed = box.mesh.V;
  posed(box.vertexAt(4, 4, 4), 0) += 1.6;
  const MatrixX3d before = posed;
  const posing::UntangleResult r = posing::TetUntangler(box.mesh.V, box.mesh.T, box.bone)(posed);
  EXPECT_EQ(r.badBefore, 6);
  EXPECT_EQ(r.fixedBad, 6);
  EXPECT_EQ(r.badAfter, 6);
  EXPECT_EQ(r.regions, 0);
  EXPECT_EQ(r.movedVertices, 0);
  EXPECT_EQ(posed, before);
}

// Two bones pressed through each other along a bar: the end of bone 1 (x ≥ 9) pushed 3 along −x, past the end
// of bone 0 (x ≤ 7), the one layer of free vertices between them (x = 8) midway. Each free vertex inside is a
// corner of tets on both bones' end faces, so it would have to lie both beyond x = 7 and before x = 6: no place
// of the free vertices alone is valid. Freeing the bone corners of the tets still bad lets the rims of both
// bones give way, while the bones' inner vertices stay rigid.
TEST(UntangleTets, FreesTheRimsOfBonesPressedThroughEachOther) {
  Box box(false, 16);
  const MatrixX3d& V = box.mesh.V;
  MatrixX3d skinned = V;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const double x = V(v, 0);
    box.bone[v] = x <= 7 ? 0 : x >= 9 ? 1 : -1;
    if (x >= 9) skinned(v, 0) = x - 3;
    else if (x > 7) skinned(v, 0) = 6.5;
  }
  const long inverted = countBelow(V, box.mesh.T, skinned, 0);
  for (const int releaseRounds : {0, 3}) {
    posing::UntangleOptions options;
    options.releaseRounds = releaseRounds;
    MatrixX3d posed = skinned;
    const posing::UntangleResult r = posing::TetUntangler(V, box.mesh.T, box.bone, options)(posed);
    double boneMove = 0, innerMove = 0;
    for (Eigen::Index v = 0; v < V.rows(); ++v) {
      if (box.bone[v] < 0) continue;
      const double move = (posed.row(v) - skinned.row(v)).norm();
      boneMove = std::max(boneMove, move);
      if (V(v, 0) <= 4 || V(v, 0) >= 12) innerMove = std::max(innerMove, move);
    }
    std::printf("bones pressed 1 through each other, %d release rounds: %ld inverted, below 0.05 %ld -> %ld, %ld "
                "bone vertices freed, moved by up to %.3f (reported %.3f), smallest ratio %.3f\n",
                releaseRounds, inverted, r.badBefore, r.badAfter, r.releasedBoneVertices, boneMove, r.maxBoneMove,
                smallestRatio(V, box.mesh.T, posed));
    EXPECT_GT(inverted, 0);
    EXPECT_EQ(r.maxBoneMove, boneMove);
    EXPECT_EQ(innerMove, 0.0);  // three layers in from the rims: rigid
    if (releaseRounds == 0) {
      EXPECT_GT(r.badAfter, 0);
      EXPECT_EQ(r.releasedBoneVertices, 0);
      EXPECT_EQ(boneMove, 0.0);
    } else {
      EXPECT_EQ(r.badAfter, 0);
      EXPECT_GE(smallestRatio(V, box.mesh.T, posed), options.minVolumeRatio);
      EXPECT_GT(r.releasedBoneVertices, 0);
    }
  }
}
