// Centres of rotation for CoR skinning (Le & Hodgins 2016; Sujar et al. 2018, eqs. 6-7): the clustered evaluation
// against the tet-by-tet reference on the four-bone bar and on a chain of many bones, and the one-bone
// fallback.
#include "vesalius/posing/bone_weights.h"
#include "vesalius/posing/rotation_centers.h"

#include "vesalius/core/error.h"

#include "posing_test_support.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace vesalius;

namespace {

// A rig-like case with many bones: a bar [0, 4·bones] × [0, 4] × [0, 4] of cubes of side 1/2 with one small
// bone per length 4 along its axis, the core |y - 2|, |z - 2| <= 1/2, 3/2 <= x - 4j <= 5/2 of bone j (27
// vertices), so tissue surrounds the bones and fills the joints. As on the MakeHuman rig (small capsule
// bones), Laplace weights leave every bone some weight everywhere; with 32 bones a vertex has 43 bone pairs
// above the cutoff on average.
test::BoneBar boneChain(int bones) {
  test::BoneBar chain{test::boxTets(8 * bones, 8, 8, 0.5), {}, Eigen::Vector3d(2.0 * bones, 2, 2)};
  chain.boneOfVertex = Eigen::VectorXi::Constant(chain.mesh.V.rows(), -1);
  for (Eigen::Index v = 0; v < chain.mesh.V.rows(); ++v) {
    const Eigen::RowVector3d x = chain.mesh.V.row(v);
    const int bone = std::min(bones - 1, int(x.x() / 4));
    const double along = x.x() - 4 * bone;
    if (std::abs(x.y() - 2) < 0.5 + 1e-9 && std::abs(x.z() - 2) < 0.5 + 1e-9 && along > 1.5 - 1e-9 && along < 2.5 + 1e-9)
      chain.boneOfVertex[v] = bone;
  }
  return chain;
}

double diagonal(const MatrixX3d& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

}  // namespace

TEST(RotationCenters, ClusteredMatchesBruteForceOnTheBar) {
  const test::BoneBar bar = test::fourBoneBar();
  const Eigen::MatrixXd W = posing::computeBoneWeights(bar.mesh.V, bar.mesh.T, bar.boneOfVertex);
  const MatrixX3d exact = posing::computeRotationCentersBruteForce(bar.mesh.V, bar.mesh.T, W);
  const MatrixX3d clustered = posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W);
  const double size = diagonal(bar.mesh.V);
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

TEST(RotationCenters, ClusteredMatchesBruteForceOnAChainOfManyBones) {
  const test::BoneBar chain = boneChain(32);
  const Eigen::MatrixXd W = posing::computeBoneWeights(chain.mesh.V, chain.mesh.T, chain.boneOfVertex);
  const MatrixX3d clustered = posing::computeRotationCenters(chain.mesh.V, chain.mesh.T, W);
  // An even sample of the vertices, and vertices of the plane between bones 15 and 16 (x = 64, at whole
  // y and z), where two bones share the weight and the centre matters most.
  std::vector<int> rows;
  for (int v = 0; v < int(W.rows()); v += 997) rows.push_back(v);
  for (int v = 0; v < int(W.rows()); ++v) {
    const Eigen::RowVector3d x = chain.mesh.V.row(v);
    if (std::abs(x.x() - 64) < 1e-9 && x.y() == std::round(x.y()) && x.z() == std::round(x.z())) rows.push_back(v);
  }
  const Eigen::VectorXi sample = Eigen::Map<const Eigen::VectorXi>(rows.data(), Eigen::Index(rows.size()));
  const MatrixX3d exact = posing::computeRotationCentersBruteForce(chain.mesh.V, chain.mesh.T, W, {}, sample);
  double worst = 0;
  for (Eigen::Index s = 0; s < sample.size(); ++s)
    worst = std::max(worst, (clustered.row(sample[s]) - exact.row(s)).norm());
  const double size = diagonal(chain.mesh.V);
  RecordProperty("max_centre_difference_over_size", testing::PrintToString(worst / size));
  std::printf("CoR centres on a chain of 32 bones (%ld vertices, %ld tets), clustered vs brute force on %ld "
              "vertices: max difference %.2e of the bounding-box diagonal\n",
              long(W.rows()), long(chain.mesh.T.rows()), long(sample.size()), worst / size);
  EXPECT_LT(worst, 1e-4 * size);
  // The joint plane's centres lie on the bar's axis near the joint (x = 64, y = z = 2).
  for (Eigen::Index s = 0; s < sample.size(); ++s)
    if (std::abs(chain.mesh.V(sample[s], 0) - 64) < 1e-9) {
      EXPECT_LT((clustered.row(sample[s]) - Eigen::RowVector3d(64, 2, 2)).norm(), 0.05) << "vertex " << sample[s];
    }
  // Parallel over pairs and vertices, each sum in a fixed order: one thread gives the same centres.
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(posing::computeRotationCenters(chain.mesh.V, chain.mesh.T, W), clustered);
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
  options = {};
  options.clusterWidth = 1e-4;  // a pair's table of cells would hold 10⁸ entries
  EXPECT_THROW(posing::computeRotationCenters(bar.mesh.V, bar.mesh.T, W, options), UsageError);
}
