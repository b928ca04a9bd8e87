// Wang et al. 2021, Fig. 21: a known smooth anisotropic plastic field on a real template, its equilibrium shape
// sampled by markers, and the fit from the undeformed template must find both the shape and the field.
#include "vesalius/fit/initial_placement.h"
#include "vesalius/fit/plastic_fit.h"

#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fem/point_springs.h"
#include "vesalius/fem/static_equilibrium.h"

#include "vesalius/io/mesh_io.h"

#include "test_plastic_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace vesalius::fit {
namespace {

// The SOFA liver (596 tets), in mm: its file units are arbitrary and about 6.4 wide.
TetMesh liverTemplate() {
  TetMesh m = io::readTetMesh(VESALIUS_TESTDATA "/liver/liver.msh");
  m.V *= 25.0;
  return m;
}

TEST(PlasticFitGroundTruth, RecoversShapeAndPlasticFieldOfAKnownDeformation) {
  const TetMesh templ = liverTemplate();
  const PlasticFem fem(templ.V, templ.T, StableNeoHookean::fromYoungPoisson(1.0, 0.45));
  const Eigen::VectorXd sTrue = test::knownPlasticField(templ);
  const MatrixX3d truth =
      PlasticFem::unflatten(solveStaticEquilibrium(fem, sTrue, PointSprings{}, PlasticFem::flatten(templ.V)).x);

  // ICP markers: the centroids of the true shape's boundary triangles.
  const MatrixX3i F = tetBoundary(templ.T);
  FitMarkers markers;
  markers.icp.resize(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    markers.icp.row(f) = (truth.row(F(f, 0)) + truth.row(F(f, 1)) + truth.row(F(f, 2))) / 3;

  // Landmarks, as in Fig. 21 (landmarks and ICP markers): every 8th surface vertex, known in both.
  for (Eigen::Index f = 0; f < F.rows(); f += 8) {
    markers.templateLandmarks.conservativeResize(markers.templateLandmarks.rows() + 1, 3);
    markers.scanLandmarks.conservativeResize(markers.scanLandmarks.rows() + 1, 3);
    markers.templateLandmarks.bottomRows(1) = templ.V.row(F(f, 0));
    markers.scanLandmarks.bottomRows(1) = truth.row(F(f, 0));
  }
  TriMesh surface;
  surface.V = templ.V;
  surface.F = F;
  const Placement placed = placeTemplate(surface, markers.templateLandmarks, markers.scanLandmarks, markers.icp);
  Eigen::VectorXd s0(sTrue.size());
  for (Eigen::Index t = 0; t < templ.T.rows(); ++t)
    s0.segment<6>(6 * t) = placed.transform.scale * identityPlasticStrain();
  const FitResult r = fitPlasticStrains(templ, placed.transform.apply(templ.V), s0, markers);

  const double size = (templ.V.colwise().maxCoeff() - templ.V.colwise().minCoeff()).norm();
  const double worst = (r.V - truth).rowwise().norm().maxCoeff();
  std::printf("ground truth: worst vertex %.3f mm of %.1f mm, ICP mean %.3f max %.3f mm\n", worst, size,
              r.icpErrors.mean(), r.icpErrors.maxCoeff());
  EXPECT_LT(worst, 0.01 * size) << "worst vertex " << worst << " mm of " << size;
  EXPECT_LT(r.icpErrors.mean(), 0.3);

  double fpError = 0;
  for (Eigen::Index t = 0; t < templ.T.rows(); ++t) {
    const Eigen::Matrix3d fit = plasticStrainMatrix(r.s.segment<6>(6 * t)),
                          want = plasticStrainMatrix(sTrue.segment<6>(6 * t));
    fpError += (fit - want).norm() / want.norm();
  }
  std::printf("ground truth: mean relative Fp error %.4f\n", fpError / double(templ.T.rows()));
  EXPECT_LT(fpError / double(templ.T.rows()), 0.1);
}

}  // namespace
}  // namespace vesalius::fit
