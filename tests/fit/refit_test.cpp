// Refits (fit/refit.h): material points carried by the fit, and the beam of Figs. 4 and 22 refitted from
// a first fit cut short, tetrahedralized afresh by TetGen between rounds, and not past a tet budget.
#include "vesalius/fit/refit.h"

#include "vesalius/core/self_intersections.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fit/point_constraints.h"
#include "vesalius/meshing/tetrahedralize.h"

#include "test_beam.h"
#include "test_tets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace vesalius::fit {
namespace {

TEST(Refit, MaterialPointsAreCarriedWhereTheFitPutThem) {
  const TetMesh box = test::boxTets(3, 3, 3, 10.0);
  Eigen::Matrix3d A;
  A << 1.2, 0.1, 0, -0.2, 0.9, 0.1, 0, 0.3, 1.1;
  const Eigen::RowVector3d b(5, -7, 2);
  const MatrixX3d fitted = (box.V * A.transpose()).rowwise() + b;
  FitMarkers m;
  m.templateLandmarks.resize(2, 3);
  m.templateLandmarks << 1, 2, 3, 25, 14, 7;
  m.scanLandmarks = MatrixX3d::Constant(2, 3, 4.0);
  m.attachmentMaterial.resize(1, 3);
  m.attachmentMaterial << 29, 0.5, 12;
  m.attachmentTargets = MatrixX3d::Constant(1, 3, -1.0);
  m.icp = MatrixX3d::Constant(3, 3, 8.0);
  const FitMarkers c = carriedMarkers(m, box, fitted);
  const MatrixX3d landmarks = (m.templateLandmarks * A.transpose()).rowwise() + b;
  const MatrixX3d attached = (m.attachmentMaterial * A.transpose()).rowwise() + b;
  EXPECT_LT((c.templateLandmarks - landmarks).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((c.attachmentMaterial - attached).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(c.scanLandmarks, m.scanLandmarks);
  EXPECT_EQ(c.attachmentTargets, m.attachmentTargets);
  EXPECT_EQ(c.icp, m.icp);
}

Remesh tetGen() {
  return [](const TriMesh& boundary) {
    meshing::TetrahedralizeOptions options;
    options.targetTets = 2000;
    return meshing::tetrahedralize(boundary, options, "refit");
  };
}

TEST(Refit, RefitsGoOnFromAFitCutShort) {
  const TetMesh beam = test_beam::beamTets();
  const FitMarkers markers = test_beam::beamMarkers(beam);
  FitOptions options;
  options.icpIterations = 1;  // the first fit stops after one ICP iteration (0.55 mm at most)
  options.maxIcpError = 0.05;
  FitRound first{beam, markers, fitPlasticStrains(beam, beam.V, identityPlasticStrain().replicate(beam.T.rows(), 1), markers, options)};
  const double firstMean = first.result.icpErrors.mean();
  ASSERT_GT(first.result.icpErrors.maxCoeff(), options.maxIcpError);
  RefitOptions refits;
  refits.refits = 3;
  const std::vector<FitRound> rounds = refit(first, options, refits, tetGen());
  ASSERT_GE(rounds.size(), 2u);
  const FitRound& last = rounds.back();
  EXPECT_NE(last.rest.T.rows(), beam.T.rows());  // a fresh mesh, not the beam's
  EXPECT_LT(last.result.icpErrors.mean(), 0.1 * firstMean);  // measured 0.214 -> 0.004 mm in one refit
  // The attachments, carried from the beam's material points, still hold where the bend takes them.
  const std::vector<PointConstraint> held =
      embedMaterialPoints(last.rest.V, last.rest.T, last.markers.attachmentMaterial, markers.attachmentTargets, 1.0);
  const Eigen::VectorXd x = PlasticFem::flatten(last.result.V);
  for (const PointConstraint& p : held) EXPECT_LT((constrainedPoint(p, x) - p.target).norm(), 1.0);
  // The beam's own surface, carried through both rounds, lies on the refitted boundary, untangled.
  const TriMesh carried = carriedSurface(tetBoundarySurface(beam.V, beam.T), rounds);
  const TriMesh fitted = tetBoundarySurface(last.result.V, last.rest.T);
  double sum = 0, farthest = 0;
  for (const ClosestPoint& c : TriangleTree(fitted.V, fitted.F).closest(carried.V)) {
    sum += std::sqrt(c.squaredDistance);
    farthest = std::max(farthest, std::sqrt(c.squaredDistance));
  }
  EXPECT_LT(sum / double(carried.V.rows()), 0.2);  // measured 0.08 mm
  EXPECT_LT(farthest, 1.0);                          // measured 0.45 mm
  EXPECT_TRUE(selfIntersections(carried.V, carried.F).empty());
  // No refit when every marker is already close.
  FitOptions loose = options;
  loose.maxIcpError = 1e3;
  EXPECT_EQ(refit(first, loose, refits, tetGen()).size(), 1u);
  // No refit on a rest shape meshed past the budget: the first round stays the result.
  RefitOptions bounded = refits;
  bounded.maxTets = rounds[1].rest.T.rows() - 1;
  const std::vector<FitRound> within = refit(first, options, bounded, tetGen());
  ASSERT_EQ(within.size(), 1u);
  EXPECT_EQ(within[0].result.V, first.result.V);
}

}  // namespace
}  // namespace vesalius::fit
