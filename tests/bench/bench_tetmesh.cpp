// Tetrahedralizing a liver at about 50k tets: the full method (TetGen with quality and volume bounds, then
// dihedral smoothing) against TetGen's bare constrained Delaunay tetrahedralization of the same surface (no
// refinement, no optimization) in the same run. Prints one markdown table row each. Two livers: the SOFA
// template (274 triangles, as the fitting of Wang et al. 2021 uses it) and the test CT's liver label surface
// (27,144 triangles), which cannot go as low as 50k tets without coarsening the surface.
//
//   build/tests/bench/bench_tetmesh
#include "vesalius/core/tet_quality.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/tetrahedralize.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <string>

using namespace vesalius;

namespace {

double peakMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

double run(const std::string& what, const TriMesh& surface, const meshing::TetrahedralizeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const TetMesh mesh = meshing::tetrahedralize(surface, options, "liver");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const TetQualityReport q = tetQualityReport(mesh.V, mesh.T);
  std::printf("| %s | %ld | %.1f° | %.2f | %.2f s | %.0f MB |\n", what.c_str(), q.tets, q.minDihedral,
              q.maxRadiusEdge, seconds, peakMegabytes());
  return seconds;
}

}  // namespace

int main() {
  const std::string data = VESALIUS_TESTDATA;
  const TriMesh liver = io::readTriMesh(data + "/liver/liver.obj");
  std::printf("| run | tets | min dihedral | max radius-edge | time | peak memory (process) |\n|---|---|---|---|---|---|\n");
  meshing::TetrahedralizeOptions bare;
  bare.radiusEdge = 0;
  bare.optimizationLevel = 0;
  const double baseline = run("template, TetGen without refinement (baseline)", liver, bare);
  meshing::TetrahedralizeOptions target;
  target.targetTets = 50000;
  const double targeted = run("template, quality, target 50k tets", liver, target);
  std::printf("\nratio to baseline: %.0fx\n\n", targeted / baseline);

  const LabelMap map = io::readLabelMap(data + "/ct-abdomen-pelvis/example_seg_total_v1_for_example_ct.nii.gz",
                                        data + "/ct-abdomen-pelvis/labels_total_v1.tsv");
  const TriMesh ctLiver = meshing::labelSurface(map, map.table.resolve("liver"));
  const double ctBaseline = run("CT liver, TetGen without refinement (baseline)", ctLiver, bare);
  const double ctQuality = run("CT liver, quality, no volume bound", ctLiver, {});
  std::printf("\nratio to baseline: %.0fx\n", ctQuality / ctBaseline);
}
