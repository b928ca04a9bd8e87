// Centres of rotation for CoR skinning (Le & Hodgins 2016; seed 001 eqs. 6-7): the clustered evaluation
// against the tet-by-tet reference, and the one-bone fallback.
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/rotation_centers.h"

#include "vesalius/core/error.h"

#include "posing_test_support.h"

#include <gtest/gtest.h>

#include <cstdio>

using namespace vesalius;

TEST(RotationCenters, ClusteredMatchesBruteForceOnTheBar) {
  const test::BoneBar bar = test::fourBoneBar();
  const Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  const MatrixX3d exact = posing::computeRotationCentersBruteForce(bar.mesh.V, bar.mesh.T, W);
  const MatrixX3d clustered = posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W);
  const double size = (bar.mesh.V.colwise().maxCoeff() - bar.mesh.V.colwise().minCoeff()).norm();
  const double worst = (clustered - exact).rowwise().norm().maxCoeff();
  RecordProperty("max_centre_difference_over_size", testing::PrintToString(worst / size));
  std::printf("CoR centres, clustered vs brute force: max difference %.2e of the bounding-box diagonal\n",
              worst / size);
  EXPECT_LT(worst, 1e-3 * size);
  // Sampling the reference gives the same rows as computing it whole.
  const Eigen::VectorXi sample = (Eigen::VectorXi(3) << 17, 1200, 3001).finished();
  const MatrixX3d sampled = posing::computeRotationCentersBruteForce(bar.mesh.V, bar.mesh.T, W, {}, sample);
  for (int s = 0; s < 3; ++s) EXPECT_EQ(sampled.row(s), exact.row(sample[s]));
}

TEST(RotationCenters, OneBoneVerticesKeepTheirPositionAndJointVerticesCentreOnTheJoint) {
  const test::BoneBar bar = test::fourBoneBar();
  const Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  const MatrixX3d centres = posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W);
  for (Eigen::Index v = 0; v < W.rows(); ++v) {
    if (bar.boneOfVertex[v] >= 0) {
      ASSERT_EQ(centres.row(v), bar.mesh.V.row(v)) << "bone vertex " << v;
    }
    // Tissue on the middle joint's plane follows bones 1 and 2 about equally; its centre lies on the
    // bar's axis near the joint, wherever the vertex is in the cross-section.
    if (bar.boneOfVertex[v] < 0 && std::abs(bar.mesh.V(v, 0) - bar.middleJoint.x()) < 1e-9) {
      EXPECT_LT((centres.row(v) - bar.middleJoint.transpose()).norm(), 1.0) << "joint vertex " << v;
    }
  }
}

TEST(RotationCenters, RefuseBadOptions) {
  const test::BoneBar bar = test::fourBoneBar();
  const Eigen::MatrixXd W = Eigen::MatrixXd::Constant(bar.mesh.V.rows(), 2, 0.5);
  posing::RotationCenterOptions options;
  options.sigma = 0.0;
  EXPECT_THROW(posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W, options), UsageError);
  EXPECT_THROW(posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W.topRows(5)), UsageError);
}
