// MakeHuman rig: default.mhskel on base.obj, default_weights.mhw, and their agreement with benchmark.bvh.
#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/skeleton_io.h"

#include <gtest/gtest.h>

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
