// MakeHuman's body shapes get base.obj's texture coordinates (io/makehuman_uv.h), on the real files of
// testdata/body: every face gets uv, they lie in the unit square, the layout is the same for every shape
// and covers a plausible part of the square without folding over itself; a mesh that is not one of the
// base mesh's body shapes is refused.
#include "vesalius/io/makehuman_uv.h"

#include "vesalius/core/error.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vesalius {
namespace {

const std::string kBody = std::string(VESALIUS_TESTDATA) + "/body/";

double signedUvArea(const TriMesh& m, Eigen::Index f) {
  const Eigen::Vector2d a = m.UV.row(m.FUV(f, 0)), b = m.UV.row(m.FUV(f, 1)), c = m.UV.row(m.FUV(f, 2));
  const Eigen::Vector2d u = b - a, v = c - a;
  return 0.5 * (u.x() * v.y() - u.y() * v.x());
}

TEST(MakeHumanUv, EveryBodyShapeGetsTheBaseMeshLayout) {
  const TriMesh base = io::readTriMesh(kBody + "base.obj");
  TriMesh first;
  for (const char* shape : {"mh_neutral_body.obj", "mh_male_young_thin_body.obj", "mh_male_young_muscular_body.obj"}) {
    const TriMesh body = io::withMakeHumanUv(io::readTriMesh(kBody + "shapes/" + shape), base, "base.obj");
    ASSERT_EQ(body.FUV.rows(), body.F.rows()) << shape;
    EXPECT_EQ(body.F.rows(), 2 * 13378) << shape;
    EXPECT_GE(body.UV.minCoeff(), 0.0) << shape;
    EXPECT_LE(body.UV.maxCoeff(), 1.0) << shape;
    if (first.UV.rows() == 0) {
      first = body;
    } else {
      EXPECT_EQ(body.UV, first.UV) << shape;
      EXPECT_EQ(body.FUV, first.FUV) << shape;
    }
  }
  // A texture layout: charts facing one way, together covering part of the square once.
  double area = 0, absolute = 0;
  for (Eigen::Index f = 0; f < first.F.rows(); ++f) {
    area += signedUvArea(first, f);
    absolute += std::abs(signedUvArea(first, f));
  }
  RecordProperty("uv_area", std::to_string(absolute));
  RecordProperty("uv_coordinates", std::to_string(first.UV.rows()));
  EXPECT_GT(std::abs(area), 0.99 * absolute);  // no triangle flipped against the others
  EXPECT_GT(absolute, 0.2);
  EXPECT_LT(absolute, 1.0);
}

TEST(MakeHumanUv, AMeshThatIsNotABodyShapeIsRefused) {
  const TriMesh base = io::readTriMesh(kBody + "base.obj");
  TriMesh body = io::readTriMesh(kBody + "shapes/mh_neutral_body.obj");
  body.F.row(7) = body.F.row(7).reverse().eval();
  EXPECT_THROW(io::withMakeHumanUv(body, base, "base.obj"), BadInput);
  TriMesh noUv = base;
  noUv.UV.resize(0, 2);
  noUv.FUV.resize(0, 3);
  EXPECT_THROW(io::withMakeHumanUv(io::readTriMesh(kBody + "shapes/mh_neutral_body.obj"), noUv, "base.obj"), BadInput);
}

}  // namespace
}  // namespace vesalius
