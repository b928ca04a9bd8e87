// Bone attachments (Wang et al. 2021, §4.1.2): on a placed box template and a sloping bone sheet below it, exactly
// the bone vertices within the radius of the placed surface are attached (checked against a brute-force
// distance), each material point lies on the template's rest surface, and the placed material point is
// the bone vertex's closest surface point.
#include "vesalius/fit/attachments.h"

#include "vesalius/linalg/similarity_transform.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include "test_tets.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace vesalius::fit {
namespace {

SimilarityTransform placement() {
  SimilarityTransform t;
  t.scale = 1.5;
  t.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  t.translation = Eigen::Vector3d(-30, 12, 80);
  return t;
}

// A sheet under the box (template space z = -0.5 at x = -10 sloping to -6.5 at x = 30), placed in the world.
TriMesh boneSheet(const SimilarityTransform& place) {
  const int n = 17;
  TriMesh bone;
  bone.V.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -10 + 2.5 * i, y = -10 + 2.5 * j;
      bone.V.row(j * n + i) = place.apply(Eigen::Vector3d(x, y, -0.5 - 0.15 * (x + 10))).transpose();
    }
  bone.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i;
      bone.F.row(f++) << a, a + 1, a + n + 1;
      bone.F.row(f++) << a, a + n + 1, a + n;
    }
  return bone;
}

double bruteForceDistance(const MatrixX3d& V, const MatrixX3i& F, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d w;
    const Eigen::Vector3d q = closestPointOnTriangle(p, V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(),
                                                     V.row(F(f, 2)).transpose(), w);
    best = std::min(best, (p - q).norm());
  }
  return best;
}

TEST(BoneAttachments, AttachesExactlyTheBoneVerticesWithinTheRadius) {
  const TetMesh box = test::boxTets(4, 4, 4, 5.0);  // [0, 20]^3
  const SimilarityTransform place = placement();
  const MatrixX3d placedV = place.apply(box.V);
  const TriMesh bone = boneSheet(place);
  const double radius = 4.0;
  const BoneAttachments a = boneAttachments(placedV, box.T, box.V, bone, radius);

  const MatrixX3i F = tetBoundary(box.T);
  Eigen::VectorXi expected = Eigen::VectorXi::Zero(bone.V.rows());
  for (Eigen::Index v = 0; v < bone.V.rows(); ++v)
    expected[v] = bruteForceDistance(placedV, F, bone.V.row(v).transpose()) <= radius;
  ASSERT_GT(expected.sum(), 10);
  ASSERT_LT(expected.sum(), bone.V.rows() / 2);
  ASSERT_EQ(a.boneVertices.size(), expected.sum());
  for (Eigen::Index k = 0; k < a.boneVertices.size(); ++k) {
    const int v = a.boneVertices[k];
    EXPECT_TRUE(expected[v]) << "bone vertex " << v;
    EXPECT_EQ(a.targets.row(k), bone.V.row(v));
    // On the rest box's surface: inside [0, 20]^3 with some coordinate on a face.
    const Eigen::Array3d X = a.material.row(k).transpose().array();
    EXPECT_TRUE((X >= -1e-9).all() && (X <= 20 + 1e-9).all()) << X.transpose();
    EXPECT_LT(std::min(X.abs().minCoeff(), (X - 20).abs().minCoeff()), 1e-9) << X.transpose();
    // Placed, it is the bone vertex's closest point on the placed surface.
    const Eigen::Vector3d placed = place.apply(Eigen::Vector3d(a.material.row(k).transpose()));
    EXPECT_NEAR((placed - bone.V.row(v).transpose()).norm(), a.distances[k], 1e-9);
    EXPECT_LE(a.distances[k], radius);
  }
}

TEST(BoneAttachments, NoneBeyondTheRadiusAndBadArgumentsAreRefused) {
  const TetMesh box = test::boxTets(2, 2, 2, 5.0);
  const TriMesh bone = boneSheet(placement());
  EXPECT_EQ(boneAttachments(box.V, box.T, box.V, bone, 0.1).boneVertices.size(), 0);
  EXPECT_THROW(boneAttachments(box.V, box.T, box.V, bone, 0.0), UsageError);
  EXPECT_THROW(boneAttachments(box.V, box.T, box.V, TriMesh{}, 1.0), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
