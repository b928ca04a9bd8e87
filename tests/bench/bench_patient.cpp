// `vesalius patient` on the shipped CT as a user runs it: the baseline without the organ map (the scan's
// skin, fat and bone class), then with its TotalSegmentator labels (organ fits, the rig), with both hips
// flexed 30 degrees, and with frame 400 of the shipped CMU motion. Prints per run its wall and CPU time,
// peak memory, its slowest stages and its ratio to the baseline; the budget for the whole command is
// 5 minutes and 6 GB on 2 cores.
#include "bench_support.h"
#include "test_data.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace vesalius;

namespace {

// The stages of report.json, slowest first, as "name s, ...".
std::string slowestStages(const nlohmann::json& report, int count) {
  std::vector<std::pair<double, std::string>> stages;
  for (const nlohmann::json& s : report["stages"]) stages.emplace_back(s["seconds"].get<double>(), s["name"].get<std::string>());
  std::sort(stages.rbegin(), stages.rend());
  std::string out;
  for (int i = 0; i < count && i < int(stages.size()); ++i) {
    char item[96];
    std::snprintf(item, sizeof item, "%s%s %.1f s", i ? ", " : "", stages[std::size_t(i)].second.c_str(),
                  stages[std::size_t(i)].first);
    out += item;
  }
  return out;
}

double run(const std::string& name, std::vector<std::string> args, const std::string& work, double baseline) {
  const std::string out = work + "/" + name;
  args.insert(args.end(), {"--out", out, "--progress", "none", "--force"});
  const bench::ProgramRun r = bench::runProgram(VESALIUS_EXE, args, out + ".log");
  if (r.exitCode != 0) {
    std::fprintf(stderr, "bench_patient: %s failed; see %s.log\n", name.c_str(), out.c_str());
    std::exit(1);
  }
  const nlohmann::json report = bench::readJson(out + "/report.json");
  std::printf("| %s | %.1f s | %.1f s | %.0f MB | %s | %s |\n", name.c_str(), r.wall, r.cpu, r.peakMb,
              baseline > 0 ? (std::to_string(r.wall / baseline).substr(0, 4) + "x").c_str() : "1x",
              slowestStages(report, 3).c_str());
  std::fflush(stdout);
  return r.wall;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string work = argc > 1 ? argv[1] : "/tmp/vesalius-bench-patient";
  fs::create_directories(work);
  const std::vector<std::string> scan{"patient", "--scan", test::kCtScan};
  std::vector<std::string> organs = scan;
  organs.insert(organs.end(), {"--organs", test::kCtLabels, "--organ-table", test::kCtLabelTable});
  std::printf("`vesalius patient` on the shipped CT (122x101x112, 3 mm), load %.2f\n\n"
              "| run | wall | CPU | peak memory | wall / baseline | slowest stages |\n|---|---|---|---|---|---|\n",
              bench::loadAverage());
  const double baseline = run("scan only (baseline)", scan, work, 0);
  run("with organs", organs, work, baseline);
  std::vector<std::string> flexed = organs;
  flexed.insert(flexed.end(), {"--pose", "femur_l=-30,0,0; femur_r=-30,0,0"});
  run("with organs, hips flexed 30", flexed, work, baseline);
  std::vector<std::string> motion = organs;
  motion.insert(motion.end(), {"--motion", std::string(VESALIUS_TESTDATA) + "/motion/01_01.bvh", "--frame", "400"});
  run("with organs, CMU frame 400", motion, work, baseline);
  return 0;
}
