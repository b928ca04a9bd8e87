// Least-squares similarity of paired points (linalg/similarity_transform.h, Umeyama 1991): a known
// similarity and its rigid part are recovered to rounding; collinear points are refused.
#include "vesalius/linalg/similarity_transform.h"

#include "vesalius/core/error.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace vesalius {
namespace {

TEST(SimilarityTransform, RecoversAKnownSimilarityAndItsRotationWhenRigid) {
  const MatrixX3d from = 20 * MatrixX3d::Random(30, 3);
  SimilarityTransform truth;
  truth.scale = 0.8;
  truth.rotation = Eigen::AngleAxisd(-1.2, Eigen::Vector3d(0.6, 0.2, -0.7).normalized()).toRotationMatrix();
  truth.translation = Eigen::Vector3d(-15, 33, 4);
  const SimilarityTransform fitted = fitSimilarity(from, truth.apply(from), Eigen::VectorXd(), true);
  EXPECT_NEAR(fitted.scale, 0.8, 1e-12);
  EXPECT_LT((fitted.rotation - truth.rotation).norm(), 1e-12);
  EXPECT_LT((fitted.translation - truth.translation).norm(), 1e-10);

  SimilarityTransform rigidTruth = truth;
  rigidTruth.scale = 1.0;
  const SimilarityTransform rigid = fitSimilarity(from, rigidTruth.apply(from), Eigen::VectorXd(), false);
  EXPECT_EQ(rigid.scale, 1.0);
  EXPECT_LT((rigid.rotation - truth.rotation).norm(), 1e-12);
}

TEST(SimilarityTransform, RefusesCollinearPoints) {
  MatrixX3d line(4, 3);
  line << 0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3;
  EXPECT_THROW(fitSimilarity(line, line, Eigen::VectorXd(), true), BadInput);
}

}  // namespace
}  // namespace vesalius
