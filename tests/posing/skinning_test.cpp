// LBS, DQS and CoR skinning of a tet mesh (seed 001 §3.5): the bar of Fig. 7, whose middle joint is bent
// by +100° and -100° and twisted by 135°, and what every skinning method must do exactly.
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/cor_skinning.h"
#include "vesalius/posing/dual_quaternion_skinning.h"
#include "vesalius/posing/linear_blend_skinning.h"
#include "vesalius/posing/rotation_centers.h"

#include "vesalius/core/error.h"

#include "posing_test_support.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <string>

using namespace vesalius;

namespace {

struct SkinnedBar {
  test::BoneBar bar;
  Eigen::MatrixXd W;
  MatrixX3d centres;
};

// Weights and centres of the bar, computed once for all tests.
const SkinnedBar& skinnedBar() {
  static const std::unique_ptr<SkinnedBar> s = [] {
    auto b = std::make_unique<SkinnedBar>();
    b->bar = test::fourBoneBar();
    b->W = posing::computeBoneWeights(b->bar.mesh.V, b->bar.mesh.T, b->bar.boneOfVertex);
    b->centres = posing::computeRotationCenters(b->bar.mesh.V, b->bar.mesh.T, b->W);
    return b;
  }();
  return *s;
}

enum class Method { lbs, dqs, cor };

MatrixX3d skin(Method m, const std::vector<Eigen::Isometry3d>& transforms) {
  const SkinnedBar& s = skinnedBar();
  switch (m) {
    case Method::lbs: return posing::linearBlendSkinning(s.bar.mesh.V, s.W, transforms);
    case Method::dqs: return posing::dualQuaternionSkinning(s.bar.mesh.V, s.W, transforms);
    case Method::cor: return posing::corSkinning(s.bar.mesh.V, s.W, s.centres, transforms);
  }
  return {};
}

const char* name(Method m) { return m == Method::lbs ? "LBS" : m == Method::dqs ? "DQS" : "CoR"; }

double barSize() { return 48.0 * std::sqrt(1.0 + 2.0 / 36.0); }  // bounding-box diagonal of the bar

}  // namespace

TEST(Skinning, IdentityTransformsReproduceTheRestMesh) {
  const std::vector<Eigen::Isometry3d> identity(4, Eigen::Isometry3d::Identity());
  for (const Method m : {Method::lbs, Method::dqs, Method::cor}) {
    const double error = (skin(m, identity) - skinnedBar().bar.mesh.V).cwiseAbs().maxCoeff();
    EXPECT_LT(error, 1e-12 * barSize()) << name(m);
  }
}

TEST(Skinning, ACommonRigidMotionMovesEveryVertexRigidly) {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translate(Eigen::Vector3d(30, -12, 7)).rotate(Eigen::AngleAxisd(2.3, Eigen::Vector3d(1, -2, 0.5).normalized()));
  const std::vector<Eigen::Isometry3d> transforms(4, motion);
  const MatrixX3d expected = (skinnedBar().bar.mesh.V * motion.linear().transpose()).rowwise() +
                             motion.translation().transpose();
  for (const Method m : {Method::lbs, Method::dqs, Method::cor})
    EXPECT_LT((skin(m, transforms) - expected).cwiseAbs().maxCoeff(), 1e-9) << name(m);
}

TEST(Skinning, HemisphereOfTheHeaviestBoneDecidesTheQuaternionSign) {
  // A rotation by 350° is the same as by -10°; blended naively with the identity it would sweep the long
  // way round. The posed mesh must not depend on which of the two equal transforms was given.
  const test::BoneBar& bar = skinnedBar().bar;
  const auto near = test::middleJointPose(bar, Eigen::Vector3d::UnitZ(), -10.0);
  const auto far = test::middleJointPose(bar, Eigen::Vector3d::UnitZ(), 350.0);
  for (const Method m : {Method::dqs, Method::cor})
    EXPECT_LT((skin(m, near) - skin(m, far)).cwiseAbs().maxCoeff(), 1e-9) << name(m);
}

// The seed reports (Fig. 7) that LBS loses volume, DQS gains and CoR keeps it. Measured as the signed
// volume of the posed tets, LBS does lose and CoR does keep it, but DQS neither gains nor loses: every DQS
// vertex turns rigidly about the joint's axis by its own angle θ, whose Jacobian determinant is
// 1 + ∇θ · (n × (x - c)), and the integral of the second term is a surface integral that vanishes when the
// axis passes through the centroid of the bar's cross-section, as here. What DQS shows instead is the
// chord error of straight-edged tets turning on arcs, which shrinks with the square of the tet size (next
// test); the DQS "bulge" is a change of shape at the joint, not of volume.
TEST(Skinning, BarOfFigure7LbsLosesVolumeCorAndDqsKeepIt) {
  const test::BoneBar& bar = skinnedBar().bar;
  struct Pose {
    const char* name;
    Eigen::Vector3d axis;
    double degrees;
  };
  for (const Pose& pose : {Pose{"bend +100", Eigen::Vector3d::UnitZ(), 100.0},
                           Pose{"bend -100", Eigen::Vector3d::UnitZ(), -100.0},
                           Pose{"twist 135", Eigen::Vector3d::UnitX(), 135.0}}) {
    const auto transforms = test::middleJointPose(bar, pose.axis, pose.degrees);
    double change[3];
    for (const Method m : {Method::lbs, Method::dqs, Method::cor}) {
      change[int(m)] = test::volumeChange(bar.mesh.V, bar.mesh.T, skin(m, transforms));
      RecordProperty(std::string(pose.name) + " " + name(m), testing::PrintToString(change[int(m)]));
    }
    std::printf("%s: volume change LBS %+.2f %%, DQS %+.2f %%, CoR %+.2f %%\n", pose.name, 100 * change[0],
                100 * change[1], 100 * change[2]);
    SCOPED_TRACE(pose.name);
    EXPECT_LT(change[int(Method::lbs)], -0.01);
    EXPECT_LT(std::abs(change[int(Method::dqs)]), 0.005);
    EXPECT_LT(std::abs(change[int(Method::cor)]), 0.02);
  }
}

TEST(Skinning, DqsVolumeChangeOnTheBarIsDiscretisationError) {
  double change[2];
  for (const int n : {1, 2}) {
    const test::BoneBar bar = test::fourBoneBar(n);
    const Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
    const auto transforms = test::middleJointPose(bar, Eigen::Vector3d::UnitZ(), 100.0);
    change[n - 1] = test::volumeChange(bar.mesh.V, bar.mesh.T, posing::dualQuaternionSkinning(bar.mesh.V, W, transforms));
  }
  std::printf("DQS bend +100: volume change %+.3f %% (tets of side 1), %+.3f %% (side 1/2)\n", 100 * change[0],
              100 * change[1]);
  RecordProperty("side 1", testing::PrintToString(change[0]));
  RecordProperty("side 1/2", testing::PrintToString(change[1]));
  EXPECT_LT(std::abs(change[1]), 0.35 * std::abs(change[0]));  // second order: a quarter, up to the weights
}

TEST(Skinning, RefusesMismatchedSizes) {
  const SkinnedBar& s = skinnedBar();
  const std::vector<Eigen::Isometry3d> three(3, Eigen::Isometry3d::Identity());
  EXPECT_THROW(posing::linearBlendSkinning(s.bar.mesh.V, s.W, three), UsageError);
  EXPECT_THROW(posing::dualQuaternionSkinning(s.bar.mesh.V, s.W, three), UsageError);
  const std::vector<Eigen::Isometry3d> four(4, Eigen::Isometry3d::Identity());
  EXPECT_THROW(posing::corSkinning(s.bar.mesh.V, s.W, s.centres.topRows(10), four), UsageError);
}
