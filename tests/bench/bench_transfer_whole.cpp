// Benchmark of whole anatomy transfers (Dicko et al. 2013; issue 7 asks for "a whole transfer under 2 min" with the
// Laplace solve's ratio against plain CG in the same run). Each case runs `vesalius transfer` twice, back to
// back: its two Laplace fields solved by the shipped multigrid-preconditioned CG (`--laplace-solver mg`) and
// by Dicko et al.'s baseline, Jacobi-preconditioned CG (`--laplace-solver cg`), both to the relative residual
// 1e-8. The program is timed as a user runs it: wall time, and CPU time of all its threads because the
// machine is shared (1-minute load average before and after each case). Stage times come from its
// `--report` ("checks": the report's rules as numbers, R1, R2, R5, R6 and the Jacobian), one column per stage
// or pair of stages, so that the columns add up to the total; "rest" is the wall time outside them (start-up,
// the fat file, the report). A stage the table does not know stops the bench. The two runs' anatomies are
// compared vertex by vertex: the solvers stop at the same residual, so they should agree closely.
// Cases: torso (the torso reference of the test CT into its own skin, 4 mm field), torso-fat (into the same
// body dilated 8 mm, its fat layer given per vertex: the R3 integration test), full-body (MakeHuman's
// neutral body with Rajagopal's bones into the thin MakeHuman body, 6 mm field). The inputs are made
// first, in WORK (default /tmp/vesalius-bench-transfer-whole), and reused if there.
// Usage: bench_transfer_whole [--work WORK] [torso|torso-fat|full-body ...]; default all three.
#include "bench_support.h"
#include "test_ct_bodies.h"

#include "vesalius/io/reference_anatomy_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace vesalius;

namespace {

const std::string kData = VESALIUS_TESTDATA;
const std::string kCt = kData + "/ct-abdomen-pelvis/";

void runVesalius(const std::vector<std::string>& args, const std::string& log) {
  const bench::ProgramRun run = bench::runProgram(VESALIUS_EXE, args, log);
  if (run.exitCode == 0) return;
  std::fprintf(stderr, "bench_transfer_whole: vesalius %s failed (exit %d), see %s\n", args[0].c_str(), run.exitCode,
               log.c_str());
  std::exit(1);
}

std::string torsoReference(const std::string& work) {
  const std::string dir = work + "/torso-reference";
  if (!fs::exists(dir + "/reference.json"))
    runVesalius({"reference", "torso", "--scan", kCt + "example_ct.nii.gz", "--labels",
                 kCt + "example_seg_total_v1_for_example_ct.nii.gz", "--label-table", kCt + "labels_total_v1.tsv",
                 "--out", dir, "--progress", "none"},
                work + "/inputs.log");
  return dir;
}

std::string fullBodyReference(const std::string& work) {
  const std::string dir = work + "/full-body-reference";
  if (!fs::exists(dir + "/reference.json"))
    runVesalius({"reference", "full-body", "--skin", kData + "/body/shapes/mh_neutral_body.obj", "--skeleton",
                 kData + "/body/default.mhskel", "--model", kData + "/skeleton-opensim/Rajagopal2016.osim", "--out",
                 dir, "--progress", "none"},
                work + "/inputs.log");
  return dir;
}

// `vesalius transfer` arguments of a case, without --laplace-solver and --out; inputs made on first use.
std::vector<std::string> caseArguments(const std::string& name, const std::string& work) {
  if (name == "torso") {
    const std::string reference = torsoReference(work);
    return {"--reference", reference, "--target-skin", reference + "/skin.obj", "--voxel-size", "4"};
  }
  if (name == "torso-fat") {
    const std::string reference = torsoReference(work), dir = work + "/torso-fat-body";
    fs::create_directories(dir);
    if (!fs::exists(dir + "/fat.txt")) {
      const std::string target = test::ctBodySurface(kCt + "example_ct.nii.gz", dir, 8.0, Eigen::Vector3d::Ones());
      test::writeFatLayer(io::readReferenceAnatomy(reference).skin, target, dir + "/fat.txt");
    }
    return {"--reference", reference, "--target-skin", dir + "/target.obj", "--fat", dir + "/fat.txt", "--voxel-size", "4"};
  }
  return {"--reference", fullBodyReference(work), "--target-skin", kData + "/body/shapes/mh_male_young_thin_body.obj",
          "--space", "makehuman", "--voxel-size", "6"};
}

struct Transfer {
  bench::ProgramRun run;
  nlohmann::json report;
  std::string out;
};

Transfer transfer(const std::string& name, const std::string& solver, const std::string& work) {
  Transfer t;
  t.out = work + "/" + name + "-" + solver;
  std::vector<std::string> args{"transfer"};
  const std::vector<std::string> given = caseArguments(name, work);
  args.insert(args.end(), given.begin(), given.end());
  args.insert(args.end(), {"--laplace-solver", solver, "--out", t.out, "--report", t.out + ".json", "--progress", "none",
                           "--force"});
  t.run = bench::runProgram(VESALIUS_EXE, args, t.out + ".log");
  if (t.run.exitCode != 0) {
    std::fprintf(stderr, "bench_transfer_whole: transfer %s with %s failed (exit %d), see %s.log\n", name.c_str(),
                 solver.c_str(), t.run.exitCode, t.out.c_str());
    std::exit(1);
  }
  std::ifstream in(t.out + ".json");
  t.report = nlohmann::json::parse(in);
  return t;
}

double stage(const Transfer& t, const std::string& name) {
  for (const nlohmann::json& s : t.report["stages"])
    if (s["name"] == name) return s["seconds"].get<double>();
  return 0;
}

double fields(const Transfer& t) { return stage(t, "skin field") + stage(t, "final field"); }

// The report's stages that the table's columns show, in their order.
const std::vector<std::string> kShownStages{"reading", "skin registration", "erosion", "sub-fat registration",
                                            "inside mask", "eroded skin distance", "reference skin distance",
                                            "skin field", "bone registration",
                                            "final field", "checks", "writing"};

// Exits if the report of `t` has a stage that no column shows: its time would be in no column and the
// columns would not add up to the total.
void requireShownStages(const Transfer& t) {
  for (const nlohmann::json& s : t.report["stages"]) {
    const std::string name = s["name"].get<std::string>();
    if (std::find(kShownStages.begin(), kShownStages.end(), name) != kShownStages.end()) continue;
    std::fprintf(stderr, "bench_transfer_whole: %s.json has the stage \"%s\", which the table has no column for\n",
                 t.out.c_str(), name.c_str());
    std::exit(1);
  }
}

// The largest distance (mm) between the same vertex or point of two transferred anatomies.
double largestDifference(const std::string& a, const std::string& b) {
  const ReferenceAnatomy x = io::readReferenceAnatomy(a), y = io::readReferenceAnatomy(b);
  double largest = 0;
  for (std::size_t t = 0; t < x.tissues.size(); ++t)
    largest = std::max(largest, (x.tissues[t].mesh.V - y.tissues[t].mesh.V).rowwise().norm().maxCoeff());
  for (std::size_t p = 0; p < x.points.size(); ++p)
    largest = std::max(largest, (x.points[p].position - y.points[p].position).norm());
  return largest;
}

void printRow(const std::string& name, const char* solver, const Transfer& t) {
  double staged = 0;
  for (const nlohmann::json& s : t.report["stages"]) staged += s["seconds"].get<double>();
  const nlohmann::json& it = t.report["metrics"]["laplace_iterations"];
  std::printf("| %s | %s | %.1f s | %.1f s | %.1f s | %.1f s | %.1f s | %.1f s (%d/%d/%d it) | %.2f s | %.1f s (%d/%d/%d it) | "
              "%.1f s | %.1f s | %.1f s | **%.1f s** | %.1f s | %.0f MB |\n",
              name.c_str(), solver, stage(t, "skin registration"), stage(t, "erosion") + stage(t, "sub-fat registration"),
              stage(t, "inside mask"), stage(t, "eroded skin distance"), stage(t, "reference skin distance"),
              stage(t, "skin field"),
              it["skin_field"][0].get<int>(), it["skin_field"][1].get<int>(), it["skin_field"][2].get<int>(),
              stage(t, "bone registration"), stage(t, "final field"), it["final_field"][0].get<int>(),
              it["final_field"][1].get<int>(), it["final_field"][2].get<int>(), stage(t, "checks"),
              stage(t, "reading") + stage(t, "writing"), t.run.wall - staged, t.run.wall,
              t.run.cpu, t.run.peakMb);
}

}  // namespace

int main(int argc, char** argv) {
  std::string work = "/tmp/vesalius-bench-transfer-whole";
  std::vector<std::string> cases;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--work" && a + 1 < argc) work = argv[++a];
    else if (arg == "torso" || arg == "torso-fat" || arg == "full-body") cases.push_back(arg);
    else {
      std::fprintf(stderr, "usage: bench_transfer_whole [--work DIR] [torso|torso-fat|full-body ...]\n");
      return 2;
    }
  }
  if (cases.empty()) cases = {"torso", "torso-fat", "full-body"};
  fs::create_directories(work);
  for (const std::string& name : cases) caseArguments(name, work);  // the inputs, before any timing
  std::printf("| case | Laplace solver | registration | erosion + sub-fat registration | inside mask | "
              "eroded skin distance | reference skin distance | skin field | bones | final field | checks | "
              "reading + writing | rest | total wall | CPU | peak memory |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::vector<std::string> ratios;
  for (const std::string& name : cases) {
    const double loadBefore = bench::loadAverage();
    const Transfer mg = transfer(name, "mg", work), cg = transfer(name, "cg", work);
    requireShownStages(mg);
    requireShownStages(cg);
    printRow(name, "MG-PCG", mg);
    printRow(name, "Jacobi-CG", cg);
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %.1f× | %.2f× | %.2f× | %.1e mm | %.3f / %.3f | %.1f → %.1f |\n",
                  name.c_str(), fields(cg) / fields(mg), cg.run.wall / mg.run.wall, cg.run.cpu / mg.run.cpu,
                  largestDifference(mg.out, cg.out), mg.report["metrics"]["jacobian_min"].get<double>(),
                  cg.report["metrics"]["jacobian_min"].get<double>(), loadBefore, bench::loadAverage());
    ratios.push_back(line);
  }
  std::printf("\n| case | CG / MG-PCG: two fields (wall) | whole transfer (wall) | whole transfer (CPU) | "
              "largest vertex difference | Jacobian min MG / CG | load |\n|---|---|---|---|---|---|---|\n");
  for (const std::string& line : ratios) std::printf("%s", line.c_str());
  return 0;
}
