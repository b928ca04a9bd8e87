// `vesalius rig` at its defaults (4 mm voxels, 100,000 tets) on MakeHuman bodies of every shape
// (tests/support/makehuman_bodies.h), each posed with CoR through the shipped CMU motion 01_01 (every Nth
// frame; 25 by default) with the volume restored and the tets repaired. The neutral body is the baseline.
// Per body: the rig's wall and CPU time and peak memory, its tets, the pose run's wall time and peak
// memory, and the worst of each quality measure over the frames (inverted tets, smallest volume ratio,
// skin volume change, tissue vertices left outside, the restoration's and the repair's largest moves).
//
//   bench_rig_bodies [WORK_DIR [EVERY]]
#include "bench_support.h"
#include "makehuman_bodies.h"

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace vesalius;

namespace {

bench::ProgramRun runOrExit(const std::vector<std::string>& args, const std::string& log) {
  const bench::ProgramRun r = bench::runProgram(VESALIUS_EXE, args, log);
  if (r.exitCode != 0) {
    std::fprintf(stderr, "bench_rig_bodies: vesalius %s failed; see %s\n", args.front().c_str(), log.c_str());
    std::exit(1);
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string work = argc > 1 ? argv[1] : "/tmp/vesalius-bench-rig-bodies";
  const int every = argc > 2 ? std::max(1, std::atoi(argv[2])) : 25;
  fs::create_directories(work);
  std::printf("`vesalius rig` at its defaults on MakeHuman bodies, then `vesalius pose --method cor` through CMU "
              "01_01 (every %d frame(s)); load %.2f\n\n"
              "| body | rig wall | rig CPU | rig peak | tets | wall / neutral | pose wall | pose peak | frames | "
              "inverted at worst | smallest volume ratio | skin at worst | left outside | restoration moved | "
              "repair moved |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
              every, bench::loadAverage());
  double baseline = 0;
  for (const test::Body& b : test::kBodies) {
    const std::string dir = work + "/" + b.name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    io::writeTriMesh(dir + "/skin.obj", test::bodySkin(b));
    const bench::ProgramRun rig = runOrExit(
        {"rig", "--skin", dir + "/skin.obj", "--skeleton", test::kBodyData + "default.mhskel", "--base-mesh",
         test::kBodyData + "base.obj", "--out", dir + "/rig", "--report", dir + "/rig.json", "--progress", "none"},
        dir + "/rig.log");
    if (baseline == 0) baseline = rig.wall;
    const long tets = bench::readJson(dir + "/rig.json")["metrics"]["tets"];
    const bench::ProgramRun pose = runOrExit(
        {"pose", "--anatomy", dir + "/rig", "--motion", std::string(VESALIUS_TESTDATA) + "/motion/01_01.bvh",
         "--frames", "0:2751", "--every", std::to_string(every), "--quality-only", "--method", "cor", "--out",
         dir + "/pose", "--progress", "none"},
        dir + "/pose.log");
    const test::QualityWorst w = test::readQualityTable(dir + "/pose/quality.tsv");
    if (!w.read) {
      std::fprintf(stderr, "bench_rig_bodies: %s/pose/quality.tsv is not pose's table\n", dir.c_str());
      return 1;
    }
    std::printf("| %s | %.1f s | %.1f s | %.0f MB | %ld | %.2fx | %.1f s | %.0f MB | %d | %ld | %.3f | %+.2f %% | %ld | "
                "%.1f mm | %.1f mm |\n",
                b.name, rig.wall, rig.cpu, rig.peakMb, tets, rig.wall / baseline, pose.wall, pose.peakMb, w.frames,
                w.inverted, w.minVolumeRatio, w.skinPct, w.leftOutside, w.restoreMove, w.untangleMove);
    std::fflush(stdout);
  }
  return 0;
}
