// Closest point on a surface and point location in a tet mesh: the trees of core against brute force,
// on real meshes, in the same run. Prints one markdown table row per method.
//
//   build/tests/bench/bench_spatial_queries
#include "vesalius/core/tet_locator.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/mesh_io.h"

#include "bench_support.h"

#include <cstdio>
#include <functional>
#include <memory>
#include <limits>
#include <random>

using namespace vesalius;
using bench::seconds;

namespace {

// Random points in the mesh's bounding box grown by 10 %.
MatrixX3d randomPoints(const MatrixX3d& V, int count) {
  const Eigen::RowVector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  const Eigen::RowVector3d pad = 0.1 * (hi - lo);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  MatrixX3d P(count, 3);
  for (int i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) P(i, a) = lo(a) - pad(a) + u(rng) * (hi(a) - lo(a) + 2 * pad(a));
  return P;
}

void row(const std::string& what, int queries, double baseline, int baselineQueries, double method) {
  const double perBaseline = baseline / baselineQueries, perMethod = method / queries;
  std::printf("| %s | %d | %.2f us | %.3f us | %.0fx |\n", what.c_str(), queries, 1e6 * perBaseline,
              1e6 * perMethod, perBaseline / perMethod);
}

void benchClosestPoint() {
  const TriMesh mesh = io::readTriMesh(std::string(VESALIUS_TESTDATA) +
                                       "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl");
  const MatrixX3d P = randomPoints(mesh.V, 100000);
  const int bruteQueries = 200;
  double sink = 0;
  const double brute = seconds([&] {
    for (int i = 0; i < bruteQueries; ++i) {
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d bary;
      for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
        const Eigen::Vector3d c = closestPointOnTriangle(P.row(i).transpose(), mesh.V.row(mesh.F(f, 0)),
                                                         mesh.V.row(mesh.F(f, 1)), mesh.V.row(mesh.F(f, 2)), bary);
        best = std::min(best, (c - P.row(i).transpose()).squaredNorm());
      }
      sink += best;
    }
  });
  std::unique_ptr<TriangleTree> tree;
  const double build = seconds([&] { tree = std::make_unique<TriangleTree>(mesh.V, mesh.F); });
  const double query = seconds([&] { sink += tree->closest(P)[0].squaredDistance; });
  row("closest point, gluteus medius, " + std::to_string(mesh.F.rows()) + " triangles (tree built in " +
          std::to_string(build) + " s)",
      int(P.rows()), brute, bruteQueries, query);
  if (sink < 0) std::puts("");
}

void benchTetLocation() {
  const TetMesh mesh = io::readTetMesh(std::string(VESALIUS_TESTDATA) + "/liver/liver.msh");
  const MatrixX3d P = randomPoints(mesh.V, 100000);
  const int bruteQueries = 20000;
  long found = 0;
  TetLocator locator(mesh.V, mesh.T);
  const double brute = seconds([&] {
    for (int i = 0; i < bruteQueries; ++i)
      for (Eigen::Index t = 0; t < mesh.T.rows(); ++t)
        if ((locator.barycentric(int(t), P.row(i).transpose()).array() >= -1e-9).all()) {
          ++found;
          break;
        }
  });
  const double query = seconds([&] {
    for (Eigen::Index i = 0; i < P.rows(); ++i) found += locator.locate(P.row(i).transpose()).has_value();
  });
  row("point location, SOFA liver, " + std::to_string(mesh.T.rows()) + " tets", int(P.rows()), brute,
      bruteQueries, query);
  if (found < 0) std::puts("");
}

}  // namespace

int main() {
  std::printf("| query | queries | brute force per query | tree per query | speed-up |\n|---|---|---|---|---|\n");
  benchClosestPoint();
  benchTetLocation();
}
