// Inside masks and signed distance fields of closed meshes (mesh_volume.h): a polygonal sphere against the
// analytic ball on oblique, anisotropic and mirrored grids; real meshes against their enclosed volume and
// Lipschitz distance fields; a TotalSegmentator label through a surface and back against itself.
#include "vesalius/meshing/mesh_volume.h"

#include "test_shapes.h"
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/label_ops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>

namespace vesalius::meshing {
namespace {

const Eigen::Vector3d kCentre(12.0, -30.0, 45.0);
constexpr double kRadius = 10.0;

enum class Tilt { Oblique, Mirrored, Sheared };
const char* name(Tilt t) { return t == Tilt::Oblique ? "oblique" : t == Tilt::Mirrored ? "mirrored" : "sheared"; }

// A grid around the ball tilted 30 degrees about z and 20 about x, with anisotropic voxels, its centre
// off the lattice. Mirrored flips the j axis (negative determinant, as a RAS-stored scan); Sheared
// leans j towards i (a direction that is not a rotation).
GridGeometry obliqueGrid(Tilt tilt) {
  GridGeometry g;
  g.size = Eigen::Vector3i(52, 56, 40);
  g.spacing = Eigen::Vector3d(0.6, 0.55, 0.8);
  g.direction =
      (Eigen::AngleAxisd(0.52, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  if (tilt == Tilt::Mirrored) g.direction.col(1) *= -1.0;
  if (tilt == Tilt::Sheared) g.direction.col(1) += 0.2 * g.direction.col(0);
  g.origin = kCentre - g.direction * g.spacing.cwiseProduct(Eigen::Vector3d(25.7, 27.6, 19.3));
  return g;
}

// Signed distance to the analytic sphere at voxel (i, j, k).
double sphereDistance(const GridGeometry& g, int i, int j, int k) {
  return (g.indexToWorld(Eigen::Vector3d(i, j, k)) - kCentre).norm() - kRadius;
}

constexpr int kLevels = 6;  // 32,768 triangles

// How far the polygon's triangles dip inside the sphere: r minus the smallest distance from the
// centre to a triangle's plane (each triangle's foot point lies inside it). Distances to the polygon
// and to the sphere differ by at most this.
double polygonGap(const TriMesh& sphere) {
  double nearest = kRadius;
  for (Eigen::Index f = 0; f < sphere.F.rows(); ++f) {
    const Eigen::Vector3d a = sphere.V.row(sphere.F(f, 0)), b = sphere.V.row(sphere.F(f, 1)),
                          c = sphere.V.row(sphere.F(f, 2));
    nearest = std::min(nearest, std::abs((b - a).cross(c - a).normalized().dot(a - kCentre)));
  }
  return kRadius - nearest;
}

TEST(MeshVolume, PolygonalSphereMaskIsTheBallAtEveryVoxelCentre) {
  const TriMesh sphere = test::sphere(kLevels, kRadius, kCentre);
  const double gap = polygonGap(sphere);
  for (Tilt tilt : {Tilt::Oblique, Tilt::Mirrored, Tilt::Sheared}) {
    SCOPED_TRACE(name(tilt));
    const GridGeometry g = obliqueGrid(tilt);
    const Grid<std::uint8_t> mask = meshInsideMask(sphere, g);
    ASSERT_EQ(mask.geometry.size, g.size);
    long wrong = 0, inside = 0;
    for (int k = 0; k < g.size.z(); ++k)
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i) {
          inside += mask.at(i, j, k);
          const double d = sphereDistance(g, i, j, k);
          if (std::abs(d) > gap) wrong += mask.at(i, j, k) != (d < 0.0);
        }
    EXPECT_EQ(wrong, 0);
    const double voxels = double(inside) * g.spacing.prod();
    EXPECT_NEAR(voxels / enclosedVolume(sphere.V, sphere.F), 1.0, 0.01);
    EXPECT_NEAR(voxels / (4.0 / 3.0 * M_PI * std::pow(kRadius, 3)), 1.0, 0.01);
  }
}

TEST(MeshVolume, PolygonalSphereSignedDistanceMatchesTheSphere) {
  const TriMesh sphere = test::sphere(kLevels, kRadius, kCentre);
  const double gap = polygonGap(sphere);
  RecordProperty("polygon_gap_mm", std::to_string(gap));
  SignedDistanceOptions options;
  options.bandMm = 3.0;
  for (Tilt tilt : {Tilt::Oblique, Tilt::Mirrored, Tilt::Sheared}) {
    SCOPED_TRACE(name(tilt));
    const GridGeometry g = obliqueGrid(tilt);
    const Grid<float> sdf = meshSignedDistance(sphere, g, options);
    double worst = 0.0;
    long inBand = 0, wrongClamp = 0;
    for (int k = 0; k < g.size.z(); ++k)
      for (int j = 0; j < g.size.y(); ++j)
        for (int i = 0; i < g.size.x(); ++i) {
          const double d = sphereDistance(g, i, j, k), value = sdf.at(i, j, k);
          if (std::abs(d) < options.bandMm - 0.05) {
            worst = std::max(worst, std::abs(value - d));
            ++inBand;
          } else if (std::abs(d) > options.bandMm + 0.05) {
            wrongClamp += value != float(d < 0 ? -options.bandMm : options.bandMm);
          }
        }
    RecordProperty(std::string(name(tilt)) + "_worst_mm", std::to_string(worst));
    EXPECT_GT(inBand, 10000);
    EXPECT_LE(worst, gap + 1e-5);  // exact up to the polygon's distance from the sphere and float round-off
    EXPECT_EQ(wrongClamp, 0);
  }
}

// Two balls in one mesh, the second inside out: no single orientation fits both, so the pseudonormal
// test stands aside and OpenVDB's signs (inside = unreachable from outside) must still give both balls.
TEST(MeshVolume, PiecesFacingDifferentWaysStillGiveBothInsides) {
  const TriMesh a = test::sphere(4, 6.0, kCentre);
  TriMesh b = test::sphere(4, 4.0, kCentre + Eigen::Vector3d(0, 0, 14.0));
  b.F.col(1).swap(b.F.col(2));
  const TriMesh both = concatenate(a, b);
  GridGeometry g;
  g.size = Eigen::Vector3i(40, 40, 70);
  g.spacing = Eigen::Vector3d::Constant(0.5);
  g.origin = kCentre - Eigen::Vector3d(9.8, 9.7, 9.9);
  const Grid<std::uint8_t> mask = meshInsideMask(both, g);
  const double volume = double(segmentation::countVoxels(mask)) * g.spacing.prod();
  EXPECT_NEAR(volume / (enclosedVolume(a.V, a.F) - enclosedVolume(b.V, b.F)), 1.0, 0.01);
}

TEST(MeshVolume, RealMeshesKeepTheirVolumeAndLipschitzDistances) {
  const std::string data = VESALIUS_TESTDATA;
  // SOFA's coarse liver has arbitrary units (about 6 across); the muscle is in mm.
  const std::vector<std::tuple<std::string, std::string, double>> cases = {
      {"liver", "/liver/liver.obj", 0.04},
      {"gluteus_medius", "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl", 1.0}};
  for (const auto& [label, path, voxel] : cases) {
    SCOPED_TRACE(path);
    const TriMesh mesh = io::readTriMesh(data + path);
    ASSERT_EQ(countEdges(mesh.F).boundary, 0);
    CoveringGridOptions cover;
    cover.voxelSizeMm = voxel;
    cover.marginMm = 4 * voxel;
    cover.maxSize = Eigen::Vector3i::Constant(1000);
    const GridGeometry g = coveringGrid({&mesh}, cover);
    ASSERT_DOUBLE_EQ(g.spacing.x(), voxel);

    const Grid<std::uint8_t> mask = meshInsideMask(mesh, g);
    const double volume = std::abs(enclosedVolume(mesh.V, mesh.F));
    const double ratio = double(segmentation::countVoxels(mask)) * g.spacing.prod() / volume;
    RecordProperty(label + "_volume_ratio", std::to_string(ratio));
    EXPECT_NEAR(ratio, 1.0, 0.01);

    // The distance field must be 1-Lipschitz between neighbouring voxels (a voxel wrongly left out of
    // the band would jump to the clamp value) and negative exactly where the mask is set.
    SignedDistanceOptions options;
    options.bandMm = 2 * voxel;
    const Grid<float> sdf = meshSignedDistance(mesh, g, options);
    double steepest = 0.0;
    long inBand = 0, signMismatch = 0;
    for (int k = 0; k + 1 < g.size.z(); ++k)
      for (int j = 0; j + 1 < g.size.y(); ++j)
        for (int i = 0; i + 1 < g.size.x(); ++i) {
          const float d = sdf.at(i, j, k);
          inBand += std::abs(d) < options.bandMm;
          signMismatch += (d < 0.0f) != bool(mask.at(i, j, k));
          for (const float next : {sdf.at(i + 1, j, k), sdf.at(i, j + 1, k), sdf.at(i, j, k + 1)})
            steepest = std::max(steepest, std::abs(double(next) - d) / voxel);
        }
    RecordProperty(label + "_steepest_step", std::to_string(steepest));
    EXPECT_GT(inBand, 10000);
    EXPECT_LE(steepest, 1.0 + 1e-4);
    EXPECT_EQ(signMismatch, 0);
  }
}

// A TotalSegmentator label -> labelSurface -> meshInsideMask on the scan's grid (RAS-stored, so a
// mirrored direction) must give the label back. Floors are the measured Dice less a margin.
TEST(MeshVolume, LabelSurfaceVoxelizesBackToItsLabel) {
  const std::string dir = std::string(VESALIUS_TESTDATA) + "/ct-abdomen-pelvis/";
  const LabelMap map =
      io::readLabelMap(dir + "example_seg_total_v1_for_example_ct.nii.gz", dir + "labels_total_v1.tsv");
  for (const auto& [name, floor] : std::vector<std::pair<std::string, double>>{
           {"liver", 0.99}, {"hip_left", 0.98}, {"gluteus_medius_left", 0.99}}) {
    SCOPED_TRACE(name);
    const Label id = map.table.resolve(name);
    const Grid<std::uint8_t> back = meshInsideMask(labelSurface(map, id), map.labels.geometry);
    const double dice = segmentation::diceCoefficient(back, segmentation::maskOf(map.labels, id));
    RecordProperty(name + "_dice", std::to_string(dice));
    EXPECT_GE(dice, floor);
  }
}

TEST(MeshVolume, OpenOrBrokenMeshesAreBadInput) {
  const GridGeometry g = obliqueGrid(Tilt::Oblique);
  TriMesh open = test::sphere(2, kRadius, kCentre);
  open.F.conservativeResize(open.F.rows() - 1, 3);
  EXPECT_THROW(meshInsideMask(open, g), BadInput);
  EXPECT_THROW(meshSignedDistance(open, g), BadInput);
  try {
    meshInsideMask(open, g);
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("open mesh (3 boundary edges)"), std::string::npos) << e.what();
  }
  TriMesh nan = test::sphere(2, kRadius, kCentre);
  nan.V(4, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(meshInsideMask(nan, g), BadInput);
  EXPECT_THROW(meshInsideMask(TriMesh{}, g), BadInput);
  EXPECT_THROW(coveringGrid({&nan}), BadInput);

  const TriMesh ball = test::sphere(2, kRadius, kCentre);
  SignedDistanceOptions noBand;
  noBand.bandMm = 0.0;
  EXPECT_THROW(meshSignedDistance(ball, g, noBand), UsageError);
}

// Every vertex lies among the grid's voxel centres with at least `margin` mm to spare on each side.
void expectCovered(const TriMesh& mesh, const GridGeometry& g, double margin) {
  EXPECT_TRUE(g.direction.isIdentity());
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::Vector3d index = g.worldToIndex(mesh.V.row(v).transpose());
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(index(a) * g.spacing(a), margin - 1e-6);
      EXPECT_GE((g.size(a) - 1 - index(a)) * g.spacing(a), margin - 1e-6);
    }
  }
}

TEST(MeshVolume, CoveringGridKeepsTheVoxelSizeUnderTheCap) {
  const TriMesh ball = test::sphere(2, kRadius, kCentre);
  CoveringGridOptions options;
  options.voxelSizeMm = 0.5;
  options.marginMm = 3.0;
  const GridGeometry g = coveringGrid({&ball}, options);
  EXPECT_DOUBLE_EQ(g.spacing.x(), 0.5);
  EXPECT_EQ(g.size, Eigen::Vector3i::Constant(53));  // (20 + 2 * 3) / 0.5 + 1
  expectCovered(ball, g, options.marginMm);
}

TEST(MeshVolume, CoveringGridGrowsTheVoxelsToFitTheCap) {
  // A body-sized box of two meshes: 600 x 100 x 1200 mm plus 5 mm margins, wanted at 1 mm.
  TriMesh wide = test::sphere(1), tall = wide;
  wide.V.col(0) *= 300.0;
  wide.V.col(1) *= 50.0;
  tall.V.col(2) *= 600.0;
  CoveringGridOptions options;
  options.voxelSizeMm = 1.0;
  options.marginMm = 5.0;
  const GridGeometry g = coveringGrid({&wide, &tall}, options);
  EXPECT_TRUE((g.size.array() <= options.maxSize.array()).all()) << g.size.transpose();
  EXPECT_EQ(g.size.x(), 250);  // the binding axis: 610 mm over 249 steps
  EXPECT_NEAR(g.spacing.x(), 610.0 / 249.0, 1e-9);
  EXPECT_TRUE(g.spacing.isApproxToConstant(g.spacing.x()));
  expectCovered(wide, g, options.marginMm);
  expectCovered(tall, g, options.marginMm);
  options.voxelSizeMm = -1.0;
  EXPECT_THROW(coveringGrid({&wide}, options), UsageError);
  EXPECT_THROW(coveringGrid({}), BadInput);
}

}  // namespace
}  // namespace vesalius::meshing
