// findNormalEdges on a synthetic ball: a bright ball (100) in a dark background (0), searched from points
// 3 mm inside its surface along the outward normals, must find the ball's surface (falling edge) to a
// fraction of a millimetre; a ball inside a brighter shell of another tissue keeps the ball's edge when
// the tissue check is on; an outer tissue within the organ's band counts as another tissue where it is two
// robust deviations darker than the organ's side; the edge of a brighter layer on the organ is not taken
// for the organ's (the plateau check); a flat image gives nothing.
#include "vesalius/segmentation/normal_edges.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vesalius::segmentation {
namespace {

constexpr double kRadius = 20.0;

// 64 mm cube of 1 mm voxels centred on the origin; value(r) by distance from the centre.
template <class F>
Image radialImage(F value) {
  GridGeometry g;
  g.size = Eigen::Vector3i::Constant(64);
  g.origin = Eigen::Vector3d::Constant(-31.5);
  Image image(g);
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i)
        image.at(i, j, k) = float(value(g.indexToWorld(Eigen::Vector3d(i, j, k)).norm()));
  return image;
}

// Unit directions spread over a sphere (a Fibonacci lattice).
MatrixX3d directions(int n) {
  MatrixX3d D(n, 3);
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = 2.399963229728653 * i;
    D.row(i) << r * std::cos(phi), r * std::sin(phi), z;
  }
  return D;
}

TEST(NormalEdges, FindsTheBallSurfaceFromInside) {
  const Image ball = radialImage([](double r) { return r < kRadius ? 100.0 : 0.0; });
  const MatrixX3d normals = directions(50), points = (kRadius - 3) * normals;
  // sigma 0.75 mm: the tissue check samples 3 mm (4 sigmas) either side, beyond the blur of the edge itself
  // (with the default 2 mm the inner side reads 93, outside a uniform ball's band of its own value ± 1 %;
  // with 1 mm the outer side still reads 0.26 above the background beyond it, more than the plateau's
  // tolerance on a uniform phantom, half a deviation of 0.5).
  NormalEdgeOptions options;
  options.sigmaMm = 0.75;
  const NormalEdges found = findNormalEdges(ball, points, normals, options);
  EXPECT_EQ(found.polarity, EdgePolarity::Falling);
  for (const NormalEdge& e : found.edges) {
    ASSERT_TRUE(e.found);
    EXPECT_NEAR(e.position.norm(), kRadius, 0.6);  // voxel-sampled surface, 0.25 mm steps
    EXPECT_NEAR(e.offsetMm, 3.0, 0.6);
    EXPECT_GT(e.confidence, 0.5);
    EXPECT_LE(e.confidence, 1.0);
  }
}

TEST(NormalEdges, TissueCheckKeepsTheOrgansEdgeBesideAStrongerOne) {
  // Organ (100) to r = 20, a thin layer (40) to 23, then a very bright shell (400) from 23: the strongest
  // change is the rising one at 23; with polarity falling and the tissue check, the organ's edge at 20.
  const Image scan = radialImage([](double r) { return r < kRadius ? 100.0 : r < 23 ? 40.0 : 400.0; });
  const MatrixX3d normals = directions(30), points = (kRadius - 4) * normals;
  NormalEdgeOptions options;
  options.polarity = EdgePolarity::Either;
  options.sigmaMm = 1.0;
  options.checkTissue = false;
  for (const NormalEdge& e : findNormalEdges(scan, points, normals, options).edges)
    EXPECT_NEAR(e.position.norm(), 23.0, 0.6) << "without the check: the strongest edge";
  options.checkTissue = true;
  for (const NormalEdge& e : findNormalEdges(scan, points, normals, options).edges) {
    ASSERT_TRUE(e.found);
    EXPECT_NEAR(e.position.norm(), kRadius, 0.6) << "with the check: the organ's edge";
  }
}

// The organ (r < kRadius) of `scan` made 10 z/r brighter: brighter towards +z, as a real organ is not uniform.
Image brighterUpwards(const Image& scan) {
  Image textured = scan;
  const GridGeometry& g = scan.geometry;
  for (int k = 0; k < 64; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const Eigen::Vector3d x = g.indexToWorld(Eigen::Vector3d(i, j, k));
        if (x.norm() < kRadius) textured.at(i, j, k) += float(10 * x.z() / x.norm());
      }
  return textured;
}

TEST(NormalEdges, OuterSideInTheOrgansBandCountsWhenTwoDeviationsDarker) {
  // Organ 100 + 10 z/r to r = 20 (brighter towards +z: robust deviation 10 · 0.5 · 1.4826 = 7.4, band 100
  // ± 14.8), then "muscle" at 92, inside the band, to the cube's edge. Where the organ reads 2 deviations
  // (14.8) above the muscle (z/r above 0.68) its falling edge at r = 20 is kept although the outer side lies
  // in the band; where the step is smaller (z/r below 0.5: at most 13) there is no edge of the organ.
  const Image scan = radialImage([](double r) { return r < kRadius ? 100.0 : 92.0; });
  const Image textured = brighterUpwards(scan);
  const MatrixX3d normals = directions(50), points = (kRadius - 3) * normals;
  NormalEdgeOptions options;
  options.sigmaMm = 1.0;
  const NormalEdges found = findNormalEdges(textured, points, normals, options);
  int kept = 0, dropped = 0;
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    const NormalEdge& e = found.edges[std::size_t(i)];
    if (normals(i, 2) > 0.75) {
      ASSERT_TRUE(e.found) << "z/r " << normals(i, 2);
      EXPECT_NEAR(e.position.norm(), kRadius, 0.6);
      ++kept;
    } else if (normals(i, 2) < 0.5) {
      EXPECT_FALSE(e.found) << "z/r " << normals(i, 2);
      ++dropped;
    }
  }
  EXPECT_EQ(kept, 6);
  EXPECT_EQ(dropped, 37);
}

// The organ 100 + 10 z/r to r = 20 (band 100 ± 14.8, deviation 7.4, as above), a brighter layer (112,
// inside the band: the diaphragm and ribs on the liver) to r = 24, then background 0. The only falling
// edge is the layer's at 24, its inner side in the band and its outer side far darker; without the plateau
// check it is found everywhere. With it, where the organ behind the layer is more than half a deviation
// (3.7) darker than the layer (z/r below 0.83; all of z/r below 0.5 asserted) the edge is refused.
TEST(NormalEdges, PlateauCheckRefusesTheEdgeOfABrighterLayerOnTheOrgan) {
  const Image scan = radialImage([](double r) { return r < kRadius ? 100.0 : r < 24 ? 112.0 : 0.0; });
  const Image textured = brighterUpwards(scan);
  const MatrixX3d normals = directions(50), points = (kRadius - 3) * normals;
  NormalEdgeOptions options;
  options.sigmaMm = 0.75;
  options.plateauMm = 0;
  const NormalEdges without = findNormalEdges(textured, points, normals, options);
  options.plateauMm = 9;
  const NormalEdges with = findNormalEdges(textured, points, normals, options);
  int refused = 0;
  for (Eigen::Index i = 0; i < normals.rows(); ++i) {
    const NormalEdge& e = without.edges[std::size_t(i)];
    ASSERT_TRUE(e.found) << "z/r " << normals(i, 2);
    EXPECT_NEAR(e.position.norm(), 24.0, 0.6) << "without the plateau check: the layer's edge";
    if (normals(i, 2) < 0.5) {
      EXPECT_FALSE(with.edges[std::size_t(i)].found) << "z/r " << normals(i, 2);
      ++refused;
    }
  }
  EXPECT_EQ(refused, 37);
}

TEST(NormalEdges, FlatImageHasNoEdgesAndBadOptionsAreRefused) {
  const Image flat = radialImage([](double) { return 7.0; });
  const MatrixX3d normals = directions(10), points = 10 * normals;
  for (const NormalEdge& e : findNormalEdges(flat, points, normals).edges) {
    EXPECT_FALSE(e.found);
    EXPECT_EQ(e.confidence, 0.0);
  }
  NormalEdgeOptions bad;
  bad.searchMm = 0;
  EXPECT_THROW(findNormalEdges(flat, points, normals, bad), UsageError);
  EXPECT_THROW(findNormalEdges(flat, points, MatrixX3d::Zero(10, 3)), UsageError);
  NormalEdgeOptions negativePlateau;
  negativePlateau.plateauMm = -1;
  EXPECT_THROW(findNormalEdges(flat, points, normals, negativePlateau), UsageError);
}

}  // namespace
}  // namespace vesalius::segmentation
