// tetrahedralize on constructed surfaces: a sphere, nested spheres (two regions), a hollow shell (a cavity
// no region claims), two spheres apart, and the inputs that must be refused before TetGen sees them.
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/tet_quality.h"
#include "vesalius/meshing/tetrahedralize.h"
#include "test_shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

namespace vesalius {
namespace {

using meshing::RegionSurface;
using meshing::TetrahedralizeOptions;

Eigen::Vector3d centroid(const TetMesh& m, Eigen::Index t) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < 4; ++k) c += m.V.row(m.T(t, k)).transpose() / 4.0;
  return c;
}

double volumeOfLabel(const TetMesh& m, int label) {
  const Eigen::VectorXd v = tetVolumes(m.V, m.T);
  const Eigen::VectorXi& labels = m.tetAttributes.integer.at(kLabel);
  double sum = 0;
  for (Eigen::Index t = 0; t < v.size(); ++t) sum += labels(t) == label ? v(t) : 0.0;
  return sum;
}

TriMesh flipped(TriMesh m) {
  m.F.col(1).swap(m.F.col(2));
  return m;
}

void expectBadInput(const std::function<void()>& run, const std::string& fragment) {
  try {
    run();
    ADD_FAILURE() << "accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Tetrahedralize, SphereFillsItsSurfaceWithGoodTets) {
  const TriMesh s = test::sphere(3, 10.0);
  const TetMesh m = meshing::tetrahedralize(s);
  const TetQualityReport r = tetQualityReport(m.V, m.T);
  RecordProperty("tets", std::to_string(r.tets));
  RecordProperty("min_dihedral", std::to_string(r.minDihedral));
  EXPECT_GT(r.tets, 200);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_EQ(r.degenerate, 0);
  EXPECT_GT(r.minVolume, 0);
  EXPECT_GE(r.minDihedral, 10.0);
  EXPECT_NEAR(r.totalVolume / enclosedVolume(s.V, s.F), 1.0, 1e-9);  // Steiner points stay on the facets
  EXPECT_NEAR(enclosedVolume(m.V, tetBoundary(m.T)), r.totalVolume, 1e-9 * r.totalVolume);
  EXPECT_TRUE((m.tetAttributes.integer.at(kLabel).array() == 1).all());
}

TEST(Tetrahedralize, VolumeBoundAndTargetCount) {
  const TriMesh s = test::sphere(3, 10.0);
  TetrahedralizeOptions o;
  o.maxVolume = 5.0;
  const TetMesh bounded = meshing::tetrahedralize(s, o);
  // TetGen does not split a tet whose new vertex would encroach on the surface: a few stay just above.
  const Eigen::VectorXd volumes = tetVolumes(bounded.V, bounded.T);
  EXPECT_LE(volumes.maxCoeff(), 5.0 * 1.02);
  EXPECT_LE((volumes.array() > 5.0).count(), volumes.size() / 100);
  o.maxVolume = 0;
  o.targetTets = 20000;
  const TetMesh target = meshing::tetrahedralize(s, o);
  RecordProperty("target_tets", std::to_string(target.T.rows()));
  EXPECT_NEAR(double(target.T.rows()) / 20000.0, 1.0, 0.15);
}

TEST(Tetrahedralize, NestedSpheresGiveTwoConformingRegions) {
  const TriMesh outer = test::sphere(3, 10.0), inner = test::sphere(3, 5.0, {1, 0, 0});
  const TetMesh m = meshing::tetrahedralizeRegions({{outer, 1, "outer"}, {inner, 7, "inner"}});
  const double vi = enclosedVolume(inner.V, inner.F), vo = enclosedVolume(outer.V, outer.F);
  EXPECT_NEAR(volumeOfLabel(m, 7), vi, 1e-9 * vi);
  EXPECT_NEAR(volumeOfLabel(m, 1), vo - vi, 1e-9 * vo);
  const Eigen::VectorXi& labels = m.tetAttributes.integer.at(kLabel);
  for (Eigen::Index t = 0; t < m.T.rows(); ++t) {
    const double r = (centroid(m, t) - Eigen::Vector3d(1, 0, 0)).norm();
    ASSERT_EQ(labels(t), r < 4.9 ? 7 : (r > 5.0 ? 1 : labels(t))) << "tet " << t << " at radius " << r;
  }
  EXPECT_EQ(tetQualityReport(m.V, m.T).inverted, 0);
}

TEST(Tetrahedralize, CavityOfAHollowShellIsLeftEmpty) {
  const TriMesh outer = test::sphere(3, 10.0), inner = test::sphere(3, 5.0);
  const TriMesh shell = concatenate(outer, flipped(inner));
  const TetMesh m = meshing::tetrahedralize(shell);
  const double expected = enclosedVolume(shell.V, shell.F);
  EXPECT_NEAR(tetVolumes(m.V, m.T).sum(), expected, 1e-9 * expected);
  for (Eigen::Index t = 0; t < m.T.rows(); ++t) ASSERT_GT(centroid(m, t).norm(), 4.5);
}

TEST(Tetrahedralize, CavityOfAHollowInsideABodyBelongsToTheBody) {
  // A hollow bone in a body: the marrow cavity is body tissue, so the mesh fills the whole body.
  const TriMesh body = test::sphere(3, 20.0), bone = concatenate(test::sphere(3, 10.0), flipped(test::sphere(3, 5.0)));
  const TetMesh m = meshing::tetrahedralizeRegions({{body, 1, "body"}, {bone, 2, "bone"}});
  const double bodyVolume = enclosedVolume(body.V, body.F), boneVolume = enclosedVolume(bone.V, bone.F);
  EXPECT_NEAR(tetVolumes(m.V, m.T).sum(), bodyVolume, 1e-9 * bodyVolume);
  EXPECT_NEAR(volumeOfLabel(m, 2), boneVolume, 1e-9 * boneVolume);
  const Eigen::VectorXi& labels = m.tetAttributes.integer.at(kLabel);
  for (Eigen::Index t = 0; t < m.T.rows(); ++t)
    if (centroid(m, t).norm() < 4.5) {
      ASSERT_EQ(labels(t), 1) << "cavity tet " << t;
    }
}

TEST(Tetrahedralize, APartTurnedInsideOutDoesNotClaimTheBodyAroundIt) {
  // A bone of two parts, one of them a crumb turned inside out (a coarse voxel surface can give one): the
  // crumb's material is not found by a ray leaving it into the body, so the bone's tets stay inside its
  // outward part and the crumb holds body.
  const Eigen::Vector3d at(10, 0, 0), crumbAt(-10, 8, 0);
  const TriMesh body = test::sphere(3, 25.0),
                bone = concatenate(test::sphere(3, 6.0, at), flipped(test::sphere(2, 2.0, crumbAt)));
  // The bone listed first: its seeds come before the body's.
  const TetMesh m = meshing::tetrahedralizeRegions({{bone, 2, "bone"}, {body, 1, "body"}});
  const Eigen::VectorXi& labels = m.tetAttributes.integer.at(kLabel);
  double farthest = 0;
  for (Eigen::Index t = 0; t < m.T.rows(); ++t)
    if (labels(t) == 2) farthest = std::max(farthest, (centroid(m, t) - at).norm());
  const TriMesh outward = test::sphere(3, 6.0, at);
  std::cout << "bone tets up to " << farthest << " mm from the bone's centre (radius 6), their volume "
            << volumeOfLabel(m, 2) << " mm^3 of " << enclosedVolume(outward.V, outward.F) << '\n';
  EXPECT_LT(farthest, 6.0);
  EXPECT_NEAR(volumeOfLabel(m, 2), enclosedVolume(outward.V, outward.F), 1e-9 * enclosedVolume(outward.V, outward.F));
  const double bodyVolume = enclosedVolume(body.V, body.F);
  EXPECT_NEAR(tetVolumes(m.V, m.T).sum(), bodyVolume, 1e-9 * bodyVolume);
}

TEST(Tetrahedralize, PartsApartAreBothFilled) {
  const TriMesh two = concatenate(test::sphere(2, 3.0), test::sphere(2, 2.0, {10, 0, 0}));
  const TetMesh m = meshing::tetrahedralize(two);
  EXPECT_NEAR(tetVolumes(m.V, m.T).sum(), enclosedVolume(two.V, two.F), 1e-9 * enclosedVolume(two.V, two.F));
}

TEST(Tetrahedralize, RefusesOpenAndCrossingSurfaces) {
  TriMesh open = test::sphere(2, 10.0);
  open.F.conservativeResize(open.F.rows() - 1, 3);
  expectBadInput([&] { meshing::tetrahedralize(open, {}, "open.stl"); }, "open.stl: open surface (3 boundary edges)");
  const TriMesh crossing = concatenate(test::sphere(2, 3.0), test::sphere(2, 3.0, {2, 0, 0}));
  expectBadInput([&] { meshing::tetrahedralize(crossing, {}, "two.stl"); }, "two.stl: self-intersecting surface");
  expectBadInput(
      [&] {
        meshing::tetrahedralizeRegions({{test::sphere(2, 3.0), 1, "body"}, {test::sphere(2, 3.0, {2, 0, 0}), 2, "bone"}});
      },
      "body: intersects bone");
  TriMesh nonManifold = concatenate(test::sphere(1), test::sphere(1, 1.0, {2, 0, 0}));
  nonManifold.F.row(nonManifold.F.rows() - 1) = nonManifold.F.row(0);  // a triangle repeated
  expectBadInput([&] { meshing::checkTetgenInput({{nonManifold, 1, "dup"}}); }, "dup: ");
}

}  // namespace
}  // namespace vesalius
