#include "vesalius/fit/initial_placement.h"

#include "vesalius/core/error.h"

#include "test_shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <iostream>
#include <vector>

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
TriMesh egg(int levels = 3) {
  TriMesh m = test::sphere(levels);
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

// The egg scaled by 1.3 and moved, as it lies, with a scan that shows only its blunt half (the grid
// begins at the egg's middle): markers on the visible surface only. The two-sided ICP places the whole
// egg exactly, its pointed end where it belongs beyond the cut: the vertices at the cut, whose closest
// points lie on the visible surface's open rim, pull nothing. (That a cut organ of another subject keeps
// its size is checked on the warped CT's kidneys, tests/patient/organ_fit_warped_test.cpp.)
TEST(InitialPlacement, AnOrganTheScanCutsIsPlacedAtItsSize) {
  const TriMesh templ = egg(4);
  SimilarityTransform truth;
  truth.scale = 1.3;
  truth.translation = Eigen::Vector3d(40, -12, 7);
  TriMesh target = templ;
  target.V = truth.apply(templ.V);
  PlacementView view;
  view.grid.spacing = Eigen::Vector3d::Constant(1.0);
  view.grid.origin = truth.translation - Eigen::Vector3d(0, 40, 30);
  view.grid.size = Eigen::Vector3i(60, 81, 61);
  // The target's faces inside the grid, and markers at their vertices.
  std::vector<Eigen::Index> inside;
  std::vector<bool> in(std::size_t(target.V.rows()));
  for (Eigen::Index v = 0; v < target.V.rows(); ++v) {
    const Eigen::Vector3d index = view.grid.worldToIndex(target.V.row(v).transpose());
    in[std::size_t(v)] = index.minCoeff() >= 0 && (index.array() <= (view.grid.size.cast<double>().array() - 1)).all();
    if (in[std::size_t(v)]) inside.push_back(v);
  }
  std::vector<Eigen::Vector3i> faces;
  for (Eigen::Index f = 0; f < target.F.rows(); ++f)
    if (in[std::size_t(target.F(f, 0))] && in[std::size_t(target.F(f, 1))] && in[std::size_t(target.F(f, 2))])
      faces.push_back(target.F.row(f).transpose());
  view.surface.V = target.V;
  view.surface.F.resize(Eigen::Index(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) view.surface.F.row(Eigen::Index(f)) = faces[f].transpose();
  MatrixX3d markers(Eigen::Index(inside.size()) / 4, 3);
  for (Eigen::Index i = 0; i < markers.rows(); ++i) markers.row(i) = target.V.row(inside[std::size_t(4 * i)]);

  const Placement alone = placeTemplate(templ, MatrixX3d(), MatrixX3d(), markers);
  const Placement cut = placeTemplate(templ, MatrixX3d(), MatrixX3d(), markers, &view);
  const Eigen::Vector3d pointed(-30, 0, 0);
  const double pointedError = (cut.transform.apply(pointed) - truth.apply(pointed)).norm();
  std::cout << markers.rows() << " markers on the visible half: scale " << alone.transform.scale
            << " from the markers alone, " << cut.transform.scale << " with the view (truth 1.3); the pointed end "
            << (alone.transform.apply(pointed) - truth.apply(pointed)).norm() << " and " << pointedError
            << " mm from its place (rms " << cut.rmsError << " mm after " << cut.iterations << " iterations)\n";
  EXPECT_NEAR(cut.transform.scale, 1.3, 1e-6);
  EXPECT_LT(pointedError, 1e-4);
}

TEST(InitialPlacement, LandmarkPairsGiveTheirSimilarity) {
  const MatrixX3d from = 20 * MatrixX3d::Random(5, 3);
  const Placement p = placeTemplate(egg(), from, knownTransform().apply(from), MatrixX3d());
  EXPECT_LT(p.rmsError, 1e-10);
  EXPECT_THROW(placeTemplate(egg(), MatrixX3d(), MatrixX3d(), MatrixX3d(2, 3)), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
