// Fitted organs bent out of the other labels' tissues (patient::bendOrgansOffLabels): a fitted organ (a
// 40 mm cube of tets) that a neighbouring label's tissue (a sphere) reaches 1.5 or 4 mm into, as a
// neighbour's notch that the template lacks; and a thin spike whose tip lies 3 mm inside the organ with no
// point of the organ inside it, as a vessel in a groove the template lacks (the organ straddles it), inside
// the scan and beyond its last slice. The promise: afterwards no point of either surface lies inside the
// other (where the scan has the label), the label's tissue does not move, the organ moves only within the
// bend's reach of the contact, its tets stay positive and its tets, surface, carried template and tissue
// move together.
#include "deepest_inside.h"
#include "test_shapes.h"
#include "test_tets.h"

#include "vesalius/core/error.h"
#include "vesalius/patient/organ_separation.h"
#include "vesalius/patient/virtual_patient.h"

#include <gtest/gtest.h>

#include <cstdio>

namespace vesalius::test {
namespace {

// The virtual patient's bend.
transfer::InsideSkinWarpOptions offLabels() { return patient::VirtualPatientOptions::offLabelsBend(); }

struct Scene {
  ReferenceAnatomy anatomy;
  patient::OrganFit fit;
  GridGeometry grid;  // the labels' grid: 2 mm voxels over [-10, 70]³ mm
};

// The organ [0, 40]³ mm in 4 mm cubes; the neighbour a sphere of radius 10 mm over the middle of the organ's
// top face, reaching `depth` below it (a negative depth: that far above it).
Scene organAndNeighbour(double depth) {
  Scene s;
  s.fit.tets = boxTets(10, 10, 10, 4.0);
  s.fit.surface = tetBoundarySurface(s.fit.tets.V, s.fit.tets.T);
  s.fit.carriedTemplate = s.fit.surface;
  s.grid.size = Eigen::Vector3i::Constant(41);
  s.grid.origin = Eigen::Vector3d::Constant(-10);
  s.grid.spacing = Eigen::Vector3d::Constant(2);
  s.anatomy.skin = sphere(3, 200.0, {20, 20, 20});
  s.anatomy.tissues.push_back({"liver", TissueKind::Organ, "", false, s.fit.surface});
  s.anatomy.tissues.push_back({"colon", TissueKind::Organ, "", false, sphere(4, 10.0, {20, 20, 50.0 - depth})});
  return s;
}

TEST(OrgansOffLabels, AnOrganReachingIntoALabelsTissueIsBentOutAndTheLabelStays) {
  for (const double depth : {1.5, 4.0}) {
    Scene s = organAndNeighbour(depth);
    const TriMesh colon = s.anatomy.tissues[1].mesh;
    const double before = deepestEitherWay(s.anatomy.tissues[0].mesh, colon);
    const transfer::TissuesBentApart bent =
        patient::bendOrgansOffLabels(s.anatomy, {"liver"}, {&s.fit}, s.grid, offLabels());
    const TriMesh& liver = s.anatomy.tissues[0].mesh;
    const double after = deepestEitherWay(liver, colon);
    const Eigen::VectorXd volumes = tetVolumes(s.fit.tets.V, s.fit.tets.T);
    const Eigen::ArrayXd offTemplate = (liver.V - s.fit.carriedTemplate.V).rowwise().norm();
    std::printf("neighbour %.1f mm into the organ: deepest %.2f mm before, %.2f after; %ld points inside before, "
                "%ld after; largest move %.2f mm; smallest tet %.3f mm³\n",
                depth, before, after, bent.insideBefore, bent.insideAfter, bent.largestMoveMm, volumes.minCoeff());
    EXPECT_GT(before, depth - 0.5);
    EXPECT_EQ(bent.insideAfter, 0);
    // The points measured are apart; a vertex of the label's tissue may still sit inside the organ by less
    // than a triangle's sag, within Dicko et al.'s tolerance of 1 mm.
    EXPECT_LE(after, 1.0);
    EXPECT_EQ(s.anatomy.tissues[1].mesh.V, colon.V);  // the label's tissue is fixed
    EXPECT_GT(volumes.minCoeff(), 0.0);
    // Tets, surface, carried template and tissue moved together.
    EXPECT_EQ(liver.V, s.fit.surface.V);
    EXPECT_LT(offTemplate.maxCoeff(), 1e-9);
    // Local: the organ's bottom face, 40 mm below the contact (beyond both reaches), does not move.
    const TriMesh unmoved = tetBoundarySurface(boxTets(10, 10, 10, 4.0).V, s.fit.tets.T);
    for (Eigen::Index v = 0; v < unmoved.V.rows(); ++v) {
      if (unmoved.V(v, 2) == 0.0) {
        EXPECT_EQ(liver.V.row(v), unmoved.V.row(v));
      }
    }
    // The organ is dented, not moved away: its top face 20 mm and more from the contact's middle stays on the face.
    for (Eigen::Index v = 0; v < unmoved.V.rows(); ++v)
      if (unmoved.V(v, 2) == 40.0 && (unmoved.V.row(v).head<2>() - Eigen::RowVector2d(20, 20)).norm() > 20.0) {
        EXPECT_NEAR(liver.V(v, 2), 40.0, 0.5);
      }
  }
}

// A thin spike from 20 mm above the organ's top face, its tip `depth` below it: no point of the organ's
// surface lies inside it, its tip lies inside the organ.
TriMesh spike(double depth) {
  TriMesh m;
  m.V.resize(4, 3);
  m.V << 19.8, 19.8, 60, 20.2, 19.8, 60, 20, 20.2, 60, 20, 20, 40 - depth;
  m.F.resize(4, 3);
  m.F << 0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 3;
  return m;
}

TEST(OrgansOffLabels, AnOrganStraddlingALabelsTissueIsDentedWhereTheScanHasIt) {
  Scene s = organAndNeighbour(-30.0);  // the sphere far above: the spike alone meets the organ
  s.anatomy.tissues[1].mesh = spike(3.0);
  const TriMesh before = s.anatomy.tissues[0].mesh;
  const transfer::TissuesBentApart bent =
      patient::bendOrgansOffLabels(s.anatomy, {"liver"}, {&s.fit}, s.grid, offLabels());
  const TriMesh& liver = s.anatomy.tissues[0].mesh;
  const double after = deepestEitherWay(liver, s.anatomy.tissues[1].mesh);
  std::printf("spike's tip 3 mm into the organ, inside the scan: %ld points inside before, %ld after; deepest %.2f mm "
              "after; largest move %.2f mm\n", bent.insideBefore, bent.insideAfter, after, bent.largestMoveMm);
  EXPECT_GT(deepestEitherWay(before, s.anatomy.tissues[1].mesh), 2.5);
  EXPECT_EQ(bent.insideBefore, 1);  // the organ's point nearest the tip's closest point on it
  EXPECT_EQ(after, 0.0);
  EXPECT_GT(tetVolumes(s.fit.tets.V, s.fit.tets.T).minCoeff(), 0.0);
  // Dented along the organ's own normal (down), not pushed sideways.
  const MatrixX3d moved = liver.V - before.V;
  EXPECT_LT(moved.col(2).minCoeff(), -3.0);
  EXPECT_LT(moved.leftCols(2).cwiseAbs().maxCoeff(), 1e-9);

  // The scan ends 1 mm above the spike's tip: the tip is the cap where the scan cut the label, no obstacle.
  Scene cut = organAndNeighbour(-30.0);
  cut.anatomy.tissues[1].mesh = spike(3.0);
  cut.grid.size.z() = 24;  // voxel centres up to z = 36 mm
  const transfer::TissuesBentApart none =
      patient::bendOrgansOffLabels(cut.anatomy, {"liver"}, {&cut.fit}, cut.grid, offLabels());
  EXPECT_EQ(none.insideBefore, 0);
  EXPECT_EQ(cut.anatomy.tissues[0].mesh.V, before.V);
}

TEST(OrgansOffLabels, OrgansApartDoNotMoveAndBadArgumentsAreRefused) {
  Scene s = organAndNeighbour(-5.0);
  const TriMesh liver = s.anatomy.tissues[0].mesh;
  const transfer::TissuesBentApart bent =
      patient::bendOrgansOffLabels(s.anatomy, {"liver"}, {&s.fit}, s.grid, offLabels());
  EXPECT_EQ(bent.insideBefore, 0);
  EXPECT_EQ(s.anatomy.tissues[0].mesh.V, liver.V);
  EXPECT_THROW(patient::bendOrgansOffLabels(s.anatomy, {"spleen"}, {&s.fit}, s.grid, {}), UsageError);
  EXPECT_THROW(patient::bendOrgansOffLabels(s.anatomy, {"liver"}, {nullptr}, s.grid, {}), UsageError);
  EXPECT_THROW(patient::bendOrgansOffLabels(s.anatomy, {"liver", "colon"}, {&s.fit}, s.grid, {}), UsageError);
}

}  // namespace
}  // namespace vesalius::test
