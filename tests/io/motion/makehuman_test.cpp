// MakeHuman rig: default.mhskel on base.obj, default_weights.mhw, and their agreement with benchmark.bvh.
#include "vesalius/core/error.h"
#include "vesalius/io/makehuman_target.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/skeleton_io.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace vesalius::io {
namespace {

const std::string kBody = std::string(VESALIUS_TESTDATA) + "/body/";

class MakeHuman : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    base_ = new Eigen::MatrixX3d(readTriMesh(kBody + "base.obj").V);
    skeleton_ = new Skeleton(readMakeHumanSkeleton(kBody + "default.mhskel", *base_));
  }
  static void TearDownTestSuite() {
    delete base_;
    delete skeleton_;
  }
  static const Joint& joint(const std::string& name) {
    const int j = skeleton_->find(name);
    if (j < 0) throw std::runtime_error("no joint " + name);
    return skeleton_->joints[std::size_t(j)];
  }
  static Eigen::MatrixX3d* base_;
  static Skeleton* skeleton_;
};
Eigen::MatrixX3d* MakeHuman::base_ = nullptr;
Skeleton* MakeHuman::skeleton_ = nullptr;

TEST_F(MakeHuman, DefaultSkeletonOnBaseMesh) {
  ASSERT_EQ(base_->rows(), 19158);
  const Skeleton& s = *skeleton_;
  ASSERT_EQ(s.joints.size(), 163u);
  EXPECT_EQ(s.joints[0].name, "root");
  for (std::size_t j = 0; j < s.joints.size(); ++j) EXPECT_LT(s.joints[j].parent, int(j)) << s.joints[j].name;
  // Joint positions are means of base.obj vertices (decimetres).
  EXPECT_TRUE(joint("root").restLocal.translation().isApprox(Eigen::Vector3d(0, 0.5639, -0.7609), 1e-12));
  EXPECT_TRUE(joint("root").tail.isApprox(Eigen::Vector3d(0, 0.16295, 0.9054), 1e-12));
  EXPECT_TRUE(joint("pelvis.R").restLocal.translation().isApprox(Eigen::Vector3d(0, 0.16295, 0.9054), 1e-12));
  EXPECT_TRUE(
      joint("upperleg01.R").restLocal.translation().isApprox(Eigen::Vector3d(-1.10365, -0.2407, -0.02155), 1e-12));
  EXPECT_TRUE(
      joint("lowerleg01.R").restLocal.translation().isApprox(Eigen::Vector3d(-0.499225, -3.377825, 0.0909), 1e-12));
  EXPECT_TRUE(joint("lowerleg01.R").restLocal.linear().isIdentity());
}

TEST_F(MakeHuman, SkeletonMatchesTheBenchmarkPoseHierarchy) {
  const Motion benchmark = readBvh(kBody + "poses/benchmark.bvh");
  ASSERT_EQ(benchmark.skeleton.joints.size(), skeleton_->joints.size());
  for (const Joint& j : benchmark.skeleton.joints) {
    const int mine = skeleton_->find(j.name);
    ASSERT_GE(mine, 0) << j.name;
    const int myParent = skeleton_->joints[std::size_t(mine)].parent;
    const std::string parent = j.parent < 0 ? "" : benchmark.skeleton.joints[std::size_t(j.parent)].name;
    EXPECT_EQ(myParent < 0 ? "" : skeleton_->joints[std::size_t(myParent)].name, parent) << j.name;
  }
}

TEST_F(MakeHuman, WeightsAreNormalisedPerVertex) {
  const SkinWeights w = readMakeHumanWeights(kBody + "default_weights.mhw", *skeleton_, int(base_->rows()));
  EXPECT_EQ(w.rows(), 19158);
  EXPECT_EQ(w.cols(), 163);
  EXPECT_EQ(w.nonZeros(), 57107);
  int weighted = 0;
  double worst = 0;
  for (Eigen::Index r = 0; r < w.outerSize(); ++r) {
    double sum = 0;
    for (SkinWeights::InnerIterator it(w, r); it; ++it) sum += it.value();
    if (sum > 0) ++weighted, worst = std::max(worst, std::abs(sum - 1));
  }
  EXPECT_EQ(weighted, 19158);
  EXPECT_LT(worst, 1e-12);
  // Vertex 1399's raw weights sum to 0.997; breast.L's 0.016 becomes 0.016 / 0.997.
  EXPECT_NEAR(w.coeff(1399, skeleton_->find("breast.L")), 0.016 / 0.997, 1e-12);
}

// A body of base.obj's topology (its "body" group, as the shipped shapes are) carries the joints with it.
TEST_F(MakeHuman, JointsFollowABodyOfItsTopology) {
  const TriMesh base = readTriMesh(kBody + "base.obj");
  const TriMesh neutral = readTriMesh(kBody + "shapes/mh_neutral_body.obj");
  ASSERT_TRUE(isMakeHumanBody(base, neutral));
  ASSERT_TRUE(isMakeHumanBody(base, base));
  const std::vector<Eigen::Isometry3d> want = skeleton_->restWorld();
  const auto largestShift = [&](const Skeleton& s, const Eigen::Matrix3d& A, const Eigen::Vector3d& b) {
    const std::vector<Eigen::Isometry3d> got = s.restWorld();
    double worst = 0;
    for (std::size_t j = 0; j < want.size(); ++j)
      worst = std::max(worst, (got[j].translation() - (A * want[j].translation() + b)).norm());
    return worst;
  };
  const std::string mhskel = kBody + "default.mhskel";
  EXPECT_LT(largestShift(readMakeHumanSkeletonOfBody(mhskel, base, neutral), Eigen::Matrix3d::Identity(),
                         Eigen::Vector3d::Zero()), 1e-12);
  // The body stretched, sheared and moved as a whole: every joint moves by the same map (the body has no
  // holes, so mean value coordinates reproduce it exactly).
  Eigen::Matrix3d A;
  A << 1.1, 0.05, 0, 0, 0.9, 0.1, 0.02, 0, 1.2;
  const Eigen::Vector3d b(0.3, -0.2, 0.5);
  TriMesh moved = neutral;
  moved.V = (neutral.V * A.transpose()).rowwise() + b.transpose();
  const double worst = largestShift(readMakeHumanSkeletonOfBody(mhskel, base, moved), A, b);
  std::printf("joints of the moved body: largest error %.2e dm\n", worst);
  EXPECT_LT(worst, 1e-6);
  // Another shape: the thin body is taller and slimmer; its knees are not the neutral body's.
  const TriMesh thin = readTriMesh(kBody + "shapes/mh_male_young_thin_body.obj");
  const Skeleton thinSkeleton = readMakeHumanSkeletonOfBody(mhskel, base, thin);
  const int knee = thinSkeleton.find("lowerleg01.L");
  const double shift = (thinSkeleton.restWorld()[std::size_t(knee)].translation() - want[std::size_t(knee)].translation()).norm();
  std::printf("thin body: left knee %.3f dm from the neutral body's\n", shift);
  EXPECT_GT(shift, 0.05);
  TriMesh other = neutral;
  other.F.row(0) = other.F.row(0).reverse().eval();
  EXPECT_FALSE(isMakeHumanBody(base, other));  // another topology: base.obj's joints
  other.V = moved.V;
  EXPECT_LT(largestShift(readMakeHumanSkeletonOfBody(mhskel, base, other), Eigen::Matrix3d::Identity(),
                         Eigen::Vector3d::Zero()), 1e-12);
}

// The shipped thin body is the base body plus two targets at weight 1 (testdata/body/SOURCE.md).
TEST_F(MakeHuman, TargetsMakeTheShippedShapes) {
  TriMesh body = readTriMesh(kBody + "shapes/mh_neutral_body.obj");
  for (const char* t : {"caucasian-male-young", "universal-male-young-minmuscle-minweight"})
    body = applyMakeHumanTarget(body, readMakeHumanTarget(kBody + "targets/" + t + ".target"));
  const TriMesh thin = readTriMesh(kBody + "shapes/mh_male_young_thin_body.obj");
  ASSERT_EQ(body.V.rows(), thin.V.rows());
  const double worst = (body.V - thin.V).rowwise().norm().maxCoeff();
  std::printf("neutral + targets vs the shipped thin body: largest difference %.2e dm\n", worst);
  EXPECT_LT(worst, 1e-9);
  EXPECT_THROW(parseMakeHumanTarget("12 0.1 0.2\n", "short.target"), BadInput);
  EXPECT_THROW(parseMakeHumanTarget("-3 0.1 0.2 0.3\n", "negative.target"), BadInput);
  EXPECT_THROW(parseMakeHumanTarget("3 0.1 nan 0.3\n", "nan.target"), BadInput);
  const MakeHumanTarget t = parseMakeHumanTarget("# comment\n\n7 0.5 -1 2 # tail\n", "ok.target");
  ASSERT_EQ(t.vertex.size(), 1);
  EXPECT_EQ(t.vertex[0], 7);
  EXPECT_EQ(t.offset.row(0), Eigen::RowVector3d(0.5, -1, 2));
}

TEST_F(MakeHuman, BadRigsAreBadInput) {
  EXPECT_THROW(readMakeHumanSkeleton(kBody + "default.mhskel", base_->topRows(1000)), BadInput);
  EXPECT_THROW(readMakeHumanWeights(kBody + "default_weights.mhw", *skeleton_, 1000), BadInput);
  Skeleton partial = *skeleton_;
  partial.joints.pop_back();
  EXPECT_THROW(parseMakeHumanWeights(R"({"weights": {"nope": [[0, 1.0]]}})", "w.mhw", partial, 10), BadInput);
  EXPECT_THROW(parseMakeHumanWeights(R"({"weights": {"root": [[0, -1.0]]}})", "w.mhw", partial, 10), BadInput);
  const Eigen::MatrixX3d v = Eigen::MatrixX3d::Zero(3, 3);
  EXPECT_THROW(
      parseMakeHumanSkeleton(R"({"joints": {"j": [0]}, "bones": {"a": {"head": "j", "tail": "j", "parent": "b"}}})",
                             "s.mhskel", v),
      BadInput);
  EXPECT_THROW(
      parseMakeHumanSkeleton(R"({"joints": {"j": [0]}, "bones": {"a": {"head": "j", "tail": "j", "parent": "b"},
                                          "b": {"head": "j", "tail": "j", "parent": "a"}}})",
                             "s.mhskel", v),
      BadInput);
  try {
    parseMakeHumanSkeleton("{\"joints\": ", "cut.mhskel", v);
    ADD_FAILURE();
  } catch (const BadInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("cut.mhskel: invalid JSON", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace vesalius::io
