// Marker suggestions (patient/marker_suggestions.h) on synthetic organs of 1 mm voxels: a bright ball and
// a bright ellipsoid in a dark background, the template a unit sphere placed on points of the organ's
// surface shifted by a few millimetres (a rough label that misses the organ). The suggestions are as many
// as asked, previews of edges found, and lie on the organ's surface (within the edge search's 0.6 mm on a
// voxel-sampled surface, as segmentation's normal-edge test); the bent template lies nearer the organ than
// the placed one did (within a voxel on average); the kept edges are the most confident spread ones; a
// template placed beyond the scan is refused naming the template.
#include "vesalius/patient/marker_suggestions.h"

#include "vesalius/core/error.h"

#include "test_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

namespace vesalius::patient {
namespace {

// The organ: the ellipsoid of semi-axes `axes` (mm) around the origin.
struct Organ {
  Eigen::Vector3d axes;
  // Distance to its surface, to first order (exact on a sphere): (ρ - 1) / |∇ρ|, ρ = |p / axes|.
  double distance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = p.cwiseQuotient(axes);
    const double rho = q.norm();
    return (rho - 1) * rho / q.cwiseQuotient(axes).norm();
  }
};

// 72 mm cube of 1 mm voxels centred on the origin: 100 inside the organ, 0 outside.
Image organImage(const Organ& organ) {
  GridGeometry g;
  g.size = Eigen::Vector3i::Constant(72);
  g.origin = Eigen::Vector3d::Constant(-35.5);
  Image image(g);
  for (int k = 0; k < 72; ++k)
    for (int j = 0; j < 72; ++j)
      for (int i = 0; i < 72; ++i)
        image.at(i, j, k) = organ.distance(g.indexToWorld(Eigen::Vector3d(i, j, k))) < 0 ? 100.0f : 0.0f;
  return image;
}

// Points on the organ's surface (a Fibonacci lattice scaled onto the ellipsoid), moved by `shift`.
MatrixX3d shiftedSurfacePoints(const Organ& organ, int n, const Eigen::Vector3d& shift) {
  MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = 2.399963229728653 * i;
    P.row(i) = (Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z).cwiseProduct(organ.axes) + shift).transpose();
  }
  return P;
}

double meanDistance(const Organ& organ, const MatrixX3d& V) {
  double sum = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) sum += std::abs(organ.distance(V.row(i).transpose()));
  return sum / double(V.rows());
}

MarkerSuggestionOptions coarse(int count) {
  MarkerSuggestionOptions o;
  o.count = count;
  o.roundPoints = 300;
  o.sigmaMm = 0.75;  // a uniform phantom's edge; see segmentation's normal-edge test for why not 2 mm
  o.templateName = "sphere.obj";
  return o;
}

TEST(MarkerSuggestions, LieOnTheOrgansSurface) {
  const TriMesh templ = test::sphere(3);
  for (const Organ& organ : {Organ{{20, 20, 20}}, Organ{{24, 17, 13}}}) {
    const Image scan = organImage(organ);
    const MatrixX3d targets = shiftedSurfacePoints(organ, 400, {3, -2, 1});
    for (int count : {30, 80}) {
      const MarkerSuggestions s = suggestMarkers(scan, templ, targets, coarse(count));
      ASSERT_EQ(int(s.kept.size()), count);
      ASSERT_EQ(int(s.found.edges.size()), 8 * count);
      EXPECT_EQ(s.found.polarity, segmentation::EdgePolarity::Falling);
      double worst = 0;
      for (std::size_t k = 0; k < s.kept.size(); ++k) {
        const segmentation::NormalEdge& e = s.found.edges[s.kept[k]];
        ASSERT_TRUE(e.found);
        worst = std::max(worst, std::abs(organ.distance(e.position)));
      }
      MarkerSuggestionOptions unbent = coarse(count);
      unbent.rounds = 0;
      const double bent = meanDistance(organ, s.placed.V),
                   placed = meanDistance(organ, suggestMarkers(scan, templ, targets, unbent).placed.V);
      std::cout << "organ " << organ.axes.transpose() << ", " << count << " suggestions: farthest " << worst
                << " mm from the surface; template " << placed << " mm off as placed, " << bent
                << " mm after bending; placement RMS " << s.placement.rmsError << " mm\n";
      EXPECT_LE(worst, 0.6);
      EXPECT_LT(bent, placed);
      EXPECT_LT(bent, 1.0);  // a voxel
      // Kept in order of confidence while they are spread: at least half of sqrt(area / count) apart.
      const double spacing = 0.5 * std::sqrt(s.area / count);
      for (std::size_t a = 0; a < s.kept.size(); ++a)
        for (std::size_t b = a + 1; b < s.kept.size(); ++b) {
          const segmentation::NormalEdge &ea = s.found.edges[s.kept[a]], &eb = s.found.edges[s.kept[b]];
          EXPECT_GE(ea.confidence, eb.confidence);
          EXPECT_GE((ea.position - eb.position).norm(), spacing);
        }
    }
  }
}

TEST(MarkerSuggestions, TemplatePlacedBeyondTheScanIsBadInput) {
  const Organ organ{{20, 20, 20}};
  const Image scan = organImage(organ);
  try {
    suggestMarkers(scan, test::sphere(2), shiftedSurfacePoints(organ, 100, {200, 0, 0}), coarse(10));
    FAIL() << "a template beyond the scan was accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("sphere.obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no triangle lies within it"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vesalius::patient
