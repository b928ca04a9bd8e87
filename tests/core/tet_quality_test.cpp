// tetQuality against values worked out by hand: the regular tet and a sliver (four points near a square).
#include "vesalius/core/tet_quality.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesalius {
namespace {

constexpr double kDegrees = 180.0 / M_PI;

TEST(TetQuality, RegularTet) {
  MatrixX3d V(4, 3);
  V << 1, 1, 1, 1, -1, -1, -1, -1, 1, -1, 1, -1;  // edge 2 sqrt(2), positively oriented
  MatrixX4i T(1, 4);
  T << 0, 1, 2, 3;
  const TetQuality q = tetQuality(V, T);
  EXPECT_NEAR(q.volume(0), 8.0 / 3.0, 1e-12);  // a^3 / (6 sqrt 2)
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(q.dihedral(0, k), std::acos(1.0 / 3.0) * kDegrees, 1e-10);
  EXPECT_NEAR(q.radiusEdge(0), std::sqrt(6.0) / 4.0, 1e-12);

  const TetQualityReport r = tetQualityReport(V, T);
  EXPECT_NEAR(r.minDihedral, 70.528779, 1e-6);
  EXPECT_EQ(r.dihedralHistogram[7], 6);
  EXPECT_EQ(r.inverted, 0);
  EXPECT_EQ(r.degenerate, 0);
}

// A(1,0,h) B(-1,0,h) C(0,1,-h) D(0,-1,-h). By symmetry the circumcentre is the origin, R = sqrt(1+h^2);
// the shortest edges are AC, AD, BC, BD = sqrt(2+4h^2). Volume = |(B-A)·((C-A)×(D-A))|/6 = 4h/3.
// At AB the faces ABC and ABD seen along x are (1,-2h) and (-1,-2h): cos = (4h^2-1)/(4h^2+1).
// At AC the outward normals are (0,4h,2) and (4h,0,-2): cos of the interior angle = 1/(1+4h^2).
TEST(TetQuality, Sliver) {
  const double h = 0.1;
  MatrixX3d V(4, 3);
  V << 1, 0, h, -1, 0, h, 0, 1, -h, 0, -1, -h;
  MatrixX4i T(1, 4);
  T << 0, 1, 2, 3;
  const TetQuality q = tetQuality(V, T);
  const double flat = std::acos((4 * h * h - 1) / (4 * h * h + 1)) * kDegrees;  // 157.38°
  const double sharp = std::acos(1 / (1 + 4 * h * h)) * kDegrees;              // 15.94°
  EXPECT_NEAR(q.volume(0), 4 * h / 3, 1e-12);
  EXPECT_NEAR(q.dihedral(0, 0), flat, 1e-9);  // AB
  EXPECT_NEAR(q.dihedral(0, 5), flat, 1e-9);  // CD
  for (int k : {1, 2, 3, 4}) EXPECT_NEAR(q.dihedral(0, k), sharp, 1e-9);
  EXPECT_NEAR(q.minDihedral(0), 15.9424, 1e-4);
  EXPECT_NEAR(q.maxDihedral(0), 157.3801, 1e-4);
  EXPECT_NEAR(q.radiusEdge(0), std::sqrt(1 + h * h) / std::sqrt(2 + 4 * h * h), 1e-12);
}

TEST(TetQuality, ReportCountsInvertedAndFlatTets) {
  MatrixX3d V(5, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 0;
  MatrixX4i T(3, 4);
  T << 0, 1, 2, 3,  // positive, volume 1/6
      0, 2, 1, 3,   // the same tet inverted
      0, 1, 4, 2;   // all four in the plane z = 0
  const TetQualityReport r = tetQualityReport(V, T);
  EXPECT_EQ(r.tets, 3);
  EXPECT_EQ(r.inverted, 1);
  EXPECT_EQ(r.degenerate, 1);
  EXPECT_NEAR(r.maxVolume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(r.minVolume, -1.0 / 6.0, 1e-15);
  EXPECT_TRUE(std::isinf(r.maxRadiusEdge));
  // The right-angled corner tet: three 90° dihedrals at the corner, three of acos(1/sqrt 3) = 54.74°.
  EXPECT_NEAR(tetQuality(V, T.topRows(1)).minDihedral(0), std::acos(1 / std::sqrt(3.0)) * kDegrees, 1e-10);
  EXPECT_EQ(r.dihedralHistogram[5], 6);  // both real tets: 3 in [50, 60) and 3 at 90° (either side of round-off)
  EXPECT_EQ(r.dihedralHistogram[8] + r.dihedralHistogram[9], 6);
}

}  // namespace
}  // namespace vesalius
