#include "vesalius/fit/initial_placement.h"

#include "vesalius/core/error.h"

#include "test_shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

namespace vesalius::fit {
namespace {

SimilarityTransform knownTransform() {
  SimilarityTransform t;
  t.scale = 1.3;
  t.rotation = (Eigen::AngleAxisd(2.1, Eigen::Vector3d(0.3, -0.8, 0.5).normalized())).toRotationMatrix();
  t.translation = Eigen::Vector3d(40, -12, 7);
  return t;
}

// An egg (asymmetric along x) so that only one principal-axis start explains the markers.
TriMesh egg() {
  TriMesh m = test::sphere(3);
  for (Eigen::Index v = 0; v < m.V.rows(); ++v) {
    const double x = m.V(v, 0);
    m.V.row(v) = Eigen::RowVector3d(30 * x, (20 - 6 * x) * m.V(v, 1), (12 - 4 * x) * m.V(v, 2));
  }
  return m;
}

TEST(InitialPlacement, SimilarityIcpFindsAScaledTurnedTemplateFromMarkersAlone) {
  const TriMesh templ = egg();
  const SimilarityTransform truth = knownTransform();
  MatrixX3d markers(templ.V.rows() / 3, 3);
  for (Eigen::Index i = 0; i < markers.rows(); ++i) markers.row(i) = truth.apply(Eigen::Vector3d(templ.V.row(3 * i))).transpose();
  const Placement p = placeTemplate(templ, MatrixX3d(), MatrixX3d(), markers);
  EXPECT_LT(p.rmsError, 0.05);
  EXPECT_NEAR(p.transform.scale, 1.3, 0.01);
  // The blunt end (x = +30) must land where it belongs, not at the pointed end.
  EXPECT_LT((p.transform.apply(Eigen::Vector3d(30, 0, 0)) - truth.apply(Eigen::Vector3d(30, 0, 0))).norm(), 0.5);
}

TEST(InitialPlacement, LandmarkPairsGiveTheirSimilarity) {
  const MatrixX3d from = 20 * MatrixX3d::Random(5, 3);
  const Placement p = placeTemplate(egg(), from, knownTransform().apply(from), MatrixX3d());
  EXPECT_LT(p.rmsError, 1e-10);
  EXPECT_THROW(placeTemplate(egg(), MatrixX3d(), MatrixX3d(), MatrixX3d(2, 3)), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
