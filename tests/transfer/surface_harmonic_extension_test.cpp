// Harmonic extension over a surface's edge graph (surface_harmonic_extension.h) on MakeHuman's skin and on
// strips: known rows kept, a constant continued as itself, the maximum principle, values rising from one
// known end of a strip to the other, a piece with nothing known at 0.
#include "vesalius/transfer/surface_harmonic_extension.h"

#include "vesalius/core/error.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/mesh_io.h"

#include <gtest/gtest.h>

#include <iostream>

using namespace vesalius;
using namespace vesalius::transfer;

namespace {

TriMesh neutralBody() {
  TriMesh m = io::readTriMesh(std::string(VESALIUS_TESTDATA) + "/body/shapes/mh_neutral_body.obj");
  m.V = io::transformPoints(m.V, io::yUpToLps(), 100.0);
  return m;
}

}  // namespace

// Known: the trunk between two heights, valued by height (two columns: S and a constant 7). Unknown
// elsewhere: the head, arms and legs.
TEST(SurfaceHarmonicExtension, KeepsKnownValuesAndTheMaximumPrinciple) {
  const TriMesh body = neutralBody();
  std::vector<char> known(std::size_t(body.V.rows()), 0);
  Eigen::MatrixXd values = Eigen::MatrixXd::Zero(body.V.rows(), 2);
  double low = 1e9, high = -1e9;
  long count = 0;
  for (Eigen::Index v = 0; v < body.V.rows(); ++v)
    if (body.V(v, 2) > 0 && body.V(v, 2) < 300 && std::abs(body.V(v, 0)) < 200) {
      known[std::size_t(v)] = 1;
      values(v, 0) = body.V(v, 2);
      values(v, 1) = 7;
      low = std::min(low, body.V(v, 2));
      high = std::max(high, body.V(v, 2));
      ++count;
    }
  ASSERT_GT(count, 100);
  const Eigen::MatrixXd x = extendHarmonically(values, known, body.F);
  double largestConstantError = 0, below = 0, above = 0;
  for (Eigen::Index v = 0; v < body.V.rows(); ++v) {
    if (known[std::size_t(v)]) {
      EXPECT_EQ(x(v, 0), values(v, 0));
      continue;
    }
    largestConstantError = std::max(largestConstantError, std::abs(x(v, 1) - 7));
    below = std::max(below, low - x(v, 0));
    above = std::max(above, x(v, 0) - high);
  }
  std::cout << count << " known; constant continued within " << largestConstantError << "; below the known range by "
            << below << " mm, above by " << above << " mm\n";
  EXPECT_LT(largestConstantError, 1e-9);
  EXPECT_LE(below, 1e-6);
  EXPECT_LE(above, 1e-6);
}

// A strip of 2 by n vertices with 0 known at one end and n - 1 at the other rises between them, within
// that range; a second strip with nothing known gets 0.
TEST(SurfaceHarmonicExtension, RisesAlongAStripAndAPieceWithNothingKnownIsZero) {
  for (const int n : {5, 40}) {
    const int count = 2 * n;
    MatrixX3i F(2 * (n - 1) * 2, 3);
    int f = 0;
    for (int piece = 0; piece < 2; ++piece)
      for (int i = 0; i + 1 < n; ++i) {
        const int o = piece * count, a = o + 2 * i, b = a + 1, c = a + 2, d = a + 3;
        F.row(f++) << a, c, b;
        F.row(f++) << b, c, d;
      }
    Eigen::MatrixXd values = Eigen::MatrixXd::Zero(2 * count, 1);
    std::vector<char> known(std::size_t(2 * count), 0);
    for (const int end : {0, n - 1})
      for (int side = 0; side < 2; ++side) {
        known[std::size_t(2 * end + side)] = 1;
        values(2 * end + side, 0) = end;
      }
    const Eigen::MatrixXd x = extendHarmonically(values, known, F);
    double otherPiece = 0, smallestRise = 1e9, outOfRange = 0;
    for (int i = 0; i < n; ++i)
      for (int side = 0; side < 2; ++side) {
        otherPiece = std::max(otherPiece, std::abs(x(count + 2 * i + side, 0)));
        outOfRange = std::max({outOfRange, -x(2 * i + side, 0), x(2 * i + side, 0) - (n - 1)});
        if (i > 0) smallestRise = std::min(smallestRise, x(2 * i + side, 0) - x(2 * (i - 1) + side, 0));
      }
    std::cout << "strip of " << n << ": smallest rise " << smallestRise << ", out of range by " << outOfRange
              << ", other piece " << otherPiece << "\n";
    EXPECT_GT(smallestRise, 0);
    EXPECT_LE(outOfRange, 0);
    EXPECT_EQ(otherPiece, 0);
  }
}

TEST(SurfaceHarmonicExtension, RejectsBadSizes) {
  const MatrixX3i F = (MatrixX3i(1, 3) << 0, 1, 2).finished();
  EXPECT_THROW(extendHarmonically(Eigen::MatrixXd::Zero(3, 1), {1, 0}, F), BadInput);
  EXPECT_THROW(extendHarmonically(Eigen::MatrixXd::Zero(2, 1), {1, 0}, F), BadInput);
}
