// `vesalius fit` with its defaults on templates of any density, run as a user runs it: brain-sized
// ellipsoids of 512 (the coarse baseline, which TetGen meshes as it is), 8,192, 32,768 and 131,072
// triangles fitted to 300 markers on the head MRI's brain (test_brain.h), and the Visible Human gluteus
// medius (30,072 triangles) to 150 markers on the test CT's gluteus_medius_left. Prints per template the
// triangles TetGen was given, the tets, the marker error, wall and CPU time and peak memory of the command.
#include "bench_support.h"
#include "test_brain.h"
#include "test_data.h"

#include "vesalius/io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

using namespace vesalius;
namespace fs = std::filesystem;

namespace {

void runOrExit(const std::vector<std::string>& args, const std::string& log) {
  if (bench::runProgram(VESALIUS_EXE, args, log).exitCode != 0) {
    std::fprintf(stderr, "bench_fit_dense: vesalius %s failed; see %s\n", args[0].c_str(), log.c_str());
    std::exit(1);
  }
}

void fitRow(const std::string& name, long triangles, const std::string& templ, const std::string& markers,
            const std::string& work) {
  const std::string out = work + "/" + name;
  const std::vector<std::string> args{"fit", "--template", templ, "--icp", markers, "--unattached", "--out",
                                      out + ".vtu", "--surface-out", out + ".vtp", "--report", out + ".json",
                                      "--progress", "none", "--force"};
  const bench::ProgramRun run = bench::runProgram(VESALIUS_EXE, args, out + ".log");
  if (run.exitCode != 0) {
    std::fprintf(stderr, "bench_fit_dense: the fit of %s failed; see %s.log\n", name.c_str(), out.c_str());
    std::exit(1);
  }
  const nlohmann::json m = bench::readJson(out + ".json")["metrics"];
  std::printf("| %s | %ld | %ld | %ld | %.2f → %.2f mm | %.1f s | %.1f s | %.0f MB |\n", name.c_str(), triangles,
              m["tetrahedralized_faces"].get<long>(), m["mesh"]["fitted_tets"].get<long>(),
              m["icp_error_mm"]["before"]["mean"].get<double>(), m["icp_error_mm"]["after"]["mean"].get<double>(),
              run.wall, run.cpu, run.peakMb);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string work = argc > 1 ? argv[1] : "/tmp/vesalius-bench-fit-dense";
  fs::create_directories(work);
  const std::string brain = work + "/brain.nii.gz", brainMarkers = work + "/brain_icp.mrk.json",
                    muscleMarkers = work + "/gmed_icp.mrk.json", log = work + "/inputs.log";
  test::writeBrainLabels(brain);
  runOrExit({"markers", "sample", "--labels", brain, "--label", "brain", "--count", "300", "--seed", "1", "--out",
             brainMarkers, "--progress", "none", "--force"},
            log);
  runOrExit({"markers", "sample", "--labels", test::kCtLabels, "--table", test::kCtLabelTable, "--label",
             "gluteus_medius_left", "--count", "150", "--seed", "1", "--out", muscleMarkers, "--progress", "none",
             "--force"},
            log);
  std::printf("`vesalius fit --template T --icp M --unattached` (defaults: about 20,000 tets), load %.2f\n\n"
              "| template | triangles | given to TetGen | tets | marker error (mean) | wall | CPU | peak memory |\n"
              "|---|---|---|---|---|---|---|---|\n",
              bench::loadAverage());
  for (const int levels : {3, 5, 6, 7}) {
    const TriMesh ellipsoid = test::brainSizedEllipsoid(levels);
    const std::string name = "ellipsoid_" + std::to_string(ellipsoid.F.rows());
    io::writeTriMesh(work + "/" + name + ".obj", ellipsoid, io::MeshWriteOptions{WriteOptions{true}});
    fitRow(name, ellipsoid.F.rows(), work + "/" + name + ".obj", brainMarkers, work);
  }
  const std::string muscle = std::string(VESALIUS_TESTDATA) + "/muscles/VHF_Left_Muscle_GluteusMedius_smooth.stl";
  fitRow("gluteus medius", io::readTriMesh(muscle).F.rows(), muscle, muscleMarkers, work);
  return 0;
}
