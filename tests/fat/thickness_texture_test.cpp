// The thickness texture (Dicko et al. 2013, §3, §5): a linear field on a plane chart reproduced texel by texel, the
// harmonic fill of the empty texels, the MakeHuman body's own uv atlas read back at its vertices, and bad
// input.
#include "vesalius/core/error.h"
#include "vesalius/fat/thickness_texture.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

namespace vesalius::fat {
namespace {

using Index = Eigen::Index;

// An n × n grid of vertices over uv [lo, hi]², lying in the plane z = 0 (mm = 100 uv).
TriMesh planeChart(int n, double lo, double hi) {
  TriMesh m;
  m.V.resize(n * n, 3);
  m.UV.resize(n * n, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = lo + (hi - lo) * i / (n - 1), v = lo + (hi - lo) * j / (n - 1);
      m.UV.row(i + n * j) << u, v;
      m.V.row(i + n * j) << 100 * u, 100 * v, 0;
    }
  m.F.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = i + n * j, b = a + 1, c = a + n, d = c + 1;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
  m.FUV = m.F;
  return m;
}

double linear(double u, double v) { return 2 + 3 * u + 5 * v; }

// The largest |value − mean of its 4-neighbours| over the filled texels, and whether all are finite.
double worstHarmonicResidual(const ThicknessTexture& t) {
  double worst = 0;
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      if (t.coverage[x + t.width * y] != ThicknessTexture::kFilled) continue;
      if (!std::isfinite(t.at(x, y))) return INFINITY;
      double sum = 0;
      int n = 0;
      for (const auto& [dx, dy] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}})
        if (x + dx >= 0 && y + dy >= 0 && x + dx < t.width && y + dy < t.height) sum += t.at(x + dx, y + dy), ++n;
      worst = std::max(worst, std::abs(t.at(x, y) - sum / n));
    }
  return worst;
}

TEST(ThicknessTexture, LinearFieldOnAPlaneChartIsReproducedInTexels) {
  const TriMesh m = planeChart(9, 0.2, 0.8);
  Eigen::VectorXd f(m.V.rows());
  for (Index v = 0; v < f.size(); ++v) f[v] = linear(m.UV(v, 0), m.UV(v, 1));
  ThicknessTextureOptions o;
  o.width = 64, o.height = 48;
  const ThicknessTexture t = rasterizeThickness(m, f, o);
  ASSERT_EQ(t.values.size(), 64u * 48u);
  // Texel centres (x + 0.5) / 64 inside [0.2, 0.8]: x = 13..50 (38 columns); rows y = 10..37 (28).
  EXPECT_EQ(t.inside, 38 * 28);
  EXPECT_EQ(t.overlapping, 0);
  double worstInside = 0, worstRim = 0;
  float lo = INFINITY, hi = -INFINITY;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const double u = (x + 0.5) / 64, v = (y + 0.5) / 48;
      const int c = t.coverage[x + 64 * y];
      if (c == ThicknessTexture::kInside) worstInside = std::max(worstInside, std::abs(t.at(x, y) - linear(u, v)));
      // Rim: the value at the nearest point of the chart.
      if (c == ThicknessTexture::kRim)
        worstRim = std::max(worstRim, std::abs(t.at(x, y) - linear(std::clamp(u, 0.2, 0.8), std::clamp(v, 0.2, 0.8))));
      if (c != ThicknessTexture::kFilled) lo = std::min(lo, t.at(x, y)), hi = std::max(hi, t.at(x, y));
    }
  EXPECT_LT(worstInside, 1e-5);  // float storage
  EXPECT_LT(worstRim, 1e-5);
  EXPECT_GT(t.rim, 0);
  EXPECT_EQ(t.inside + t.rim + t.filled, 64 * 48);
  // Filled texels: finite, within the range of the fixed ones, each the mean of its neighbours.
  for (std::size_t i = 0; i < t.values.size(); ++i) {
    EXPECT_GE(t.values[i], lo - 1e-5);
    EXPECT_LE(t.values[i], hi + 1e-5);
  }
  const double residual = worstHarmonicResidual(t);
  std::cout << "plane: " << t.inside << " inside, " << t.rim << " rim, " << t.filled << " filled texels, "
            << t.sweeps << " sweeps, worst harmonic residual " << residual << "\n";
  EXPECT_LT(residual, 1e-4 * (hi - lo));
  // Read back at the vertices: exact in the chart, and at its edge to within the rim's clamping.
  const Eigen::VectorXd back = sampleTextureAtVertices(t, m);
  for (Index v = 0; v < f.size(); ++v) {
    const bool edge = m.UV(v, 0) == 0.2 || m.UV(v, 0) == 0.8 || m.UV(v, 1) == 0.2 || m.UV(v, 1) == 0.8;
    EXPECT_NEAR(back[v], f[v], edge ? 0.5 * (3.0 / 64 + 5.0 / 48) : 1e-5) << v;
  }
}

TEST(ThicknessTexture, ConstantFieldFillsConstant) {
  const TriMesh m = planeChart(3, 0.4, 0.6);
  const ThicknessTexture t = rasterizeThickness(m, Eigen::VectorXd::Constant(9, 7.5), {32, 32});
  for (float x : t.values) EXPECT_FLOAT_EQ(x, 7.5f);
  EXPECT_EQ(t.sweeps, 1);
}

TEST(ThicknessTexture, MakeHumanBodyAtlasReadsBackAtItsVertices) {
  // base.obj's "body" group (the first group, id 0) with MakeHuman's own uv atlas.
  const TriMesh base = io::readTriMesh(std::string(VESALIUS_TESTDATA) + "/body/base.obj");
  const Eigen::MatrixXi& group = base.faceAttributes.integer.at("group");
  TriMesh body;
  body.V = io::transformPoints(base.V, io::yUpToLps(), 100);
  body.UV = base.UV;
  std::vector<Index> keep;
  for (Index f = 0; f < base.F.rows(); ++f)
    if (group(f, 0) == 0) keep.push_back(f);
  body.F.resize(Index(keep.size()), 3);
  body.FUV.resize(Index(keep.size()), 3);
  for (std::size_t i = 0; i < keep.size(); ++i)
    body.F.row(Index(i)) = base.F.row(keep[i]), body.FUV.row(Index(i)) = base.FUV.row(keep[i]);
  ASSERT_EQ(body.F.rows(), 2 * 13378);
  // A field linear in position: 1 mm per 100 mm to the left, 0.5 mm per 100 mm up, 3 mm at the origin.
  Eigen::VectorXd f = (3 + body.V.col(0).array() / 100 + body.V.col(2).array() / 200).matrix();
  ThicknessTextureOptions o;
  o.width = o.height = 512;
  const ThicknessTexture t = rasterizeThickness(body, f, o);
  const Eigen::VectorXd back = sampleTextureAtVertices(t, body);
  std::vector<char> used(body.V.rows(), 0);
  for (Index k = 0; k < body.F.size(); ++k) used[body.F.data()[k]] = 1;
  std::vector<double> error;
  for (Index v = 0; v < body.V.rows(); ++v)
    if (used[v]) error.push_back(std::abs(back[v] - f[v]));
  std::sort(error.begin(), error.end());
  const double median = error[error.size() / 2], p99 = error[std::size_t(0.99 * double(error.size()))];
  const double range = f.maxCoeff() - f.minCoeff();
  std::cout << "MakeHuman atlas 512²: " << t.inside << " inside, " << t.rim << " rim, " << t.filled << " filled, "
            << t.overlapping << " overlapping texels; " << error.size() << " vertices, |error| median " << median
            << ", 99th percentile " << p99 << ", max " << error.back() << " mm (field range " << range << " mm)\n";
  EXPECT_EQ(error.size(), 13380u);
  EXPECT_LT(median, 0.01);
  EXPECT_LT(p99, 0.1);
  EXPECT_LT(worstHarmonicResidual(t), 1e-4 * range);
}

TEST(ThicknessTexture, MissingUvNonFiniteValuesAndBadSizesAreRejected) {
  TriMesh m = planeChart(3, 0.2, 0.8);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(9, 1.0);
  TriMesh noUv = m;
  noUv.UV.resize(0, 2);
  noUv.FUV.resize(0, 3);
  try {
    rasterizeThickness(noUv, f, {}, "skin.stl");
    ADD_FAILURE() << "accepted";
  } catch (const BadInput& e) {
    EXPECT_STREQ(e.what(), "skin.stl: the mesh has no texture coordinates (uv)");
  }
  EXPECT_THROW(sampleTextureAtVertices(ThicknessTexture(), noUv), BadInput);
  Eigen::VectorXd g = f;
  g[4] = std::nan("");
  EXPECT_THROW(rasterizeThickness(m, g), BadInput);
  EXPECT_THROW(rasterizeThickness(m, Eigen::VectorXd::Constant(4, 1.0)), BadInput);
  EXPECT_THROW(rasterizeThickness(m, f, {0, 16}), UsageError);
  m.UV.array() += 3;  // the chart lies outside the texture
  EXPECT_THROW(rasterizeThickness(m, f, {16, 16}), BadInput);
  EXPECT_THROW(sampleTexture(ThicknessTexture(), m.UV), UsageError);
}

}  // namespace
}  // namespace vesalius::fat
