// Winding numbers by the dipole tree (beta 3, the default) against the exact sum over every triangle
// (beta 0), in the same run, on OpenSim's left hip bone (246 triangles) and on a polygonal sphere of
// 32,768 triangles: time per 20,000 points spread over the bounding box, the ratio, and the largest
// difference; then closedSurface on the hip bone at its default resolution (64) and 1,500 faces.
#include "bench_support.h"
#include "test_shapes.h"

#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/closed_surface.h"
#include "vesalius/meshing/winding_number.h"

#include <cstdio>
#include <random>
#include <string>

namespace {

using namespace vesalius;

void compare(const char* name, const TriMesh& mesh) {
  const Eigen::Vector3d lo = mesh.V.colwise().minCoeff(), hi = mesh.V.colwise().maxCoeff();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  MatrixX3d P(20000, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    for (int a = 0; a < 3; ++a) P(i, a) = lo[a] + u(rng) * (hi[a] - lo[a]);
  Eigen::VectorXd exact, fast;
  const double exactSeconds = bench::seconds([&] { exact = meshing::windingNumbers(mesh.V, mesh.F, P, {0.0}); });
  const double fastSeconds = bench::seconds([&] { fast = meshing::windingNumbers(mesh.V, mesh.F, P); });
  std::printf("| %s | %ld | %.3f s | %.3f s | %.1f | %.4f |\n", name, long(mesh.F.rows()), exactSeconds, fastSeconds,
              exactSeconds / fastSeconds, (fast - exact).cwiseAbs().maxCoeff());
}

}  // namespace

int main() {
  const TriMesh pelvis = io::readTriMesh(std::string(VESALIUS_TESTDATA) + "/skeleton-opensim/Geometry/l_pelvis.vtp");
  std::printf("| mesh | triangles | exact | dipole tree | ratio | max difference |\n|---|---|---|---|---|---|\n");
  compare("OpenSim l_pelvis", pelvis);
  compare("sphere", test::sphere(6, 10.0));
  meshing::ClosedSurfaceOptions options;
  options.targetFaces = 1500;
  TriMesh closed;
  const double s = bench::seconds([&] { closed = meshing::closedSurface(pelvis, options); });
  std::printf("closedSurface(l_pelvis, resolution 64, 1500 faces): %.2f s, %ld triangles\n", s, long(closed.F.rows()));
  return 0;
}
