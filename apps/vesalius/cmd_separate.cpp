// vesalius separate: fitted organs that touch pushed apart where they overlap (Wang et al. 2021, §4.1.4), each
// mesh moved only in a contact region around its penetrating vertices (fit/interpenetration.h).
#include "command_runner.h"
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/fit/interpenetration.h"
#include "vesalius/io/mesh_io.h"

#include <filesystem>
#include <iomanip>
#include <iostream>

namespace fs = std::filesystem;

namespace vesalius::cli {

namespace {

struct SeparateOptions {
  std::vector<std::string> meshes;
  std::string out;
  fit::InterpenetrationOptions solver;
  CommonOptions common;
};

std::string outputPath(const SeparateOptions& o, const std::string& in) {
  return (fs::path(o.out) / fs::path(in).filename()).string();
}

// Every output is refused before any work if it is an input or two inputs share a file name, and the
// folder if it exists (without --force) or holds an input; the folder is written whole at the end
// (core/atomic_file.h), so that a run either writes every mesh or none.
void checkOutputs(const SeparateOptions& o) {
  if (o.meshes.size() < 2) throw UsageError("separate: give at least two --mesh");
  std::vector<std::string> outs;
  for (const std::string& in : o.meshes) {
    const std::string out = outputPath(o, in);
    for (const std::string& other : outs)
      if (other == out) throw UsageError(in + ": another --mesh has the same file name; rename one");
    std::error_code ec;
    for (const std::string& input : o.meshes)
      if (fs::equivalent(input, out, ec)) throw UsageError(out + ": is also an input; choose another --out folder");
    outs.push_back(out);
  }
  checkOutputFolder(o.out, o.common.writeOptions());
}

TetMesh readFitted(const std::string& path) {
  TetMesh mesh = io::readTetMesh(path);
  if (mesh.T.rows() == 0) throw BadInput(path, "has no tetrahedra (separate needs the fitted tet meshes, e.g. fit --out)");
  return mesh;
}

void runSeparate(const SeparateOptions& o, CommandRun& run) {
  checkOutputs(o);
  for (const std::string& m : o.meshes) run.report.input("mesh", m);
  run.report.parameter("rings", o.solver.rings);
  run.report.parameter("max_rounds", o.solver.maxRounds);
  run.report.parameter("clearance_mm", o.solver.clearance);

  std::vector<TetMesh> meshes;
  for (const std::string& m : o.meshes) meshes.push_back(readFitted(m));
  std::vector<fit::InterpenetrationReport> pairs;
  {
    auto timer = run.report.time("separate");
    pairs = fit::removeInterpenetrations(meshes, o.solver);
  }
  std::size_t k = 0;
  for (std::size_t i = 1; i < meshes.size(); ++i)
    for (std::size_t j = 0; j < i; ++j, ++k) {
      const fit::InterpenetrationReport& r = pairs[k];
      const std::string a = fs::path(o.meshes[i]).filename().string(), b = fs::path(o.meshes[j]).filename().string();
      run.report.metric("pair", {{"meshes", a + " / " + b},
                                 {"penetrating_vertices_before", r.penetratingBefore},
                                 {"penetrating_vertices_after", r.penetratingAfter},
                                 {"rounds", r.rounds},
                                 {"region_tets", {r.regionTets[0], r.regionTets[1]}},
                                 {"max_displacement_mm", r.maxDisplacement}});
      std::cout << a << " / " << b << ": " << r.penetratingBefore << " -> " << r.penetratingAfter
                << " penetrating boundary vertices, largest move " << std::fixed << std::setprecision(2)
                << r.maxDisplacement << " mm, regions " << r.regionTets[0] << " + " << r.regionTets[1] << " tets\n";
    }
  writeFolderAtomically(o.out, o.common.writeOptions(), [&](const std::string& staging) {
    for (std::size_t i = 0; i < meshes.size(); ++i)
      io::writeTetMesh(staging + "/" + fs::path(o.meshes[i]).filename().string(), meshes[i]);
  });
  for (const std::string& in : o.meshes) run.report.output("mesh", outputPath(o, in));
}

}  // namespace

void addSeparateCommand(CLI::App& app) {
  auto o = std::make_shared<SeparateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "separate", "Push fitted organs that overlap apart, moving each only near the contact (Wang et al. 2021, §4.1.4)");
  cmd->add_option("--mesh", o->meshes,
                  "A fitted tet mesh (.vtu .vtk .msh), world mm; repeat, in fitting order: each is pushed out of "
                  "the ones before it")
      ->required();
  cmd->add_option("--out", o->out, "Folder for the separated meshes (same file names as the inputs)")->required();
  cmd->add_option("--rings", o->solver.rings, "Rings of tets grown around the penetrating ones (the paper's 5)")
      ->check(CLI::Range(0, 50))
      ->capture_default_str();
  cmd->add_option("--clearance", o->solver.clearance, "How far beyond the other surface a pushed vertex aims, mm")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--max-rounds", o->solver.maxRounds, "Most re-detections and solves per pair and of sweeps")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer(
      "Example (two muscles fitted one after the other):\n"
      "  vesalius separate --mesh gluteus_medius.vtu --mesh gluteus_minimus.vtu --out separated/\n"
      "Nothing outside the contact regions moves; a mesh wholly inside another is refused (exit 4).");
  cmd->callback([o] { runCommand("separate", o->common, [&](CommandRun& run) { runSeparate(*o, run); }); });
}

}  // namespace vesalius::cli
