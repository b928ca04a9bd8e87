// Surfaces of labels whose shape is known: a voxelized ball on an oblique, anisotropic grid. The surface
// must be closed, one piece, outward, in world (LPS) coordinates, and enclose the ball's volume.
#include "vesalius/meshing/label_surface.h"

#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"
#include "test_label_maps.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesalius::meshing {
namespace {

const Eigen::Vector3d kCentre(12.0, -30.0, 45.0);
constexpr double kRadius = 10.0;

// A ball of label 3 (and a smaller one of label 7) on a grid tilted 30 degrees about z and 20 about x.
LabelMap balls() {
  GridGeometry g;
  g.size = Eigen::Vector3i(48, 52, 40);
  g.spacing = Eigen::Vector3d(0.6, 0.55, 0.8);
  g.direction =
      (Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  g.origin = kCentre - g.direction * g.spacing.cwiseProduct(Eigen::Vector3d(24, 26, 20));
  LabelMap map = test::paintedLabelMap(g, [](const Eigen::Vector3d& p) {
    if ((p - kCentre - Eigen::Vector3d(0, 0, 13)).norm() <= 2.5) return 7;
    return (p - kCentre).norm() <= kRadius ? 3 : 0;
  });
  map.table.add({3, "ball"});
  map.table.add({7, "small"});
  return map;
}

TEST(LabelSurface, BallOnAnObliqueGridIsClosedOutwardAndInPlace) {
  const LabelMap map = balls();
  const TriMesh mesh = labelSurface(map, 3);
  const io::TriMeshSummary s = io::summarize(mesh);
  EXPECT_TRUE(s.closed);
  EXPECT_EQ(s.components, 1);
  ASSERT_TRUE(s.volume.has_value());
  const double ball = 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  EXPECT_NEAR(*s.volume / ball, 1.0, 0.02);
  const Eigen::Vector3d centroid = mesh.V.colwise().mean();
  EXPECT_LT((centroid - kCentre).norm(), 0.3);
  double worst = 0;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    worst = std::max(worst, std::abs((mesh.V.row(v).transpose() - kCentre).norm() - kRadius));
  EXPECT_LT(worst, 0.6);  // within a voxel of the sphere
  ASSERT_TRUE(mesh.faceAttributes.integer.count(kLabel));
  EXPECT_EQ(mesh.faceAttributes.integer.at(kLabel).minCoeff(), 3);
}

TEST(LabelSurface, DecimationKeepsTheShape) {
  SurfaceOptions options;
  options.targetFaces = 2000;
  const TriMesh mesh = labelSurface(balls(), 3, options);
  const io::TriMeshSummary s = io::summarize(mesh);
  EXPECT_LE(s.triangles, 2200);
  EXPECT_TRUE(s.closed);
  EXPECT_NEAR(*s.volume / (4.0 / 3.0 * M_PI * std::pow(kRadius, 3)), 1.0, 0.03);
}

TEST(LabelSurface, OneSurfacePerLabelByName) {
  const std::vector<LabelSurface> surfaces = labelSurfaces(balls(), {});
  ASSERT_EQ(surfaces.size(), 2u);
  EXPECT_EQ(surfaces[0].name, "ball");
  EXPECT_EQ(surfaces[1].name, "small");
  EXPECT_TRUE(io::summarize(surfaces[1].mesh).closed);
}

TEST(LabelSurface, MirroredGridStillGivesAnOutwardSurface) {
  // A direction with negative determinant (one axis flipped) turns marching-cubes triangles inside out.
  LabelMap map = balls();
  map.labels.geometry.direction.col(0) *= -1.0;
  const TriMesh mesh = labelSurface(map, 3);
  const io::TriMeshSummary s = io::summarize(mesh);
  EXPECT_TRUE(s.closed);
  ASSERT_TRUE(s.volume.has_value());
  EXPECT_GT(*s.volume, 0.0);
}

TEST(LabelSurface, VolumeRestorationIsSkippedForShellsTooThinToCarryIt) {
  // A one-voxel shell: smoothing collapses it, and the offset that would restore it exceeds half a voxel.
  LabelMap map = balls();
  for (Label& v : map.labels.values) v = v == 3 ? 0 : v;
  const GridGeometry& g = map.labels.geometry;
  for (int k = 0; k < g.size.z(); ++k)
    for (int j = 0; j < g.size.y(); ++j)
      for (int i = 0; i < g.size.x(); ++i) {
        const double r = (g.indexToWorld(Eigen::Vector3d(i, j, k)) - kCentre).norm();
        if (r <= kRadius && r > kRadius - 0.6) map.labels.at(i, j, k) = 3;
      }
  // The crossing check is off in both: it would try less smoothing, where the offset may fit.
  SurfaceOptions restore, keep;
  restore.avoidSelfIntersections = keep.avoidSelfIntersections = false;
  keep.preserveVolume = false;
  const TriMesh restored = labelSurface(map, 3, restore), raw = labelSurface(map, 3, keep);
  EXPECT_TRUE(restored.V.isApprox(raw.V));
}

TEST(LabelSurface, BadOptionsAreUsageErrors) {
  SurfaceOptions options;
  options.passBand = 0.0;
  EXPECT_THROW(labelSurface(balls(), 3, options), UsageError);
  options = {};
  options.targetFaces = -5;
  EXPECT_THROW(labelSurface(balls(), 3, options), UsageError);
  options = {};
  options.smoothingIterations = 1;  // VTK's windowed sinc cannot do one iteration
  EXPECT_THROW(labelSurface(balls(), 3, options), UsageError);
}

TEST(LabelSurface, MissingLabelIsBadInput) { EXPECT_THROW(labelSurface(balls(), 9), BadInput); }

}  // namespace
}  // namespace vesalius::meshing
