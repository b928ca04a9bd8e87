// `vesalius separate` end to end: two overlapping boxes written as fitted meshes come back as the library
// separates them (fit/interpenetration.h, tested on its own in tests/fit), with the report's counts;
// bad inputs give one line and a non-zero exit, and nothing is written.
#include "run_command.h"

#include "vesalius/fit/interpenetration.h"
#include "vesalius/io/mesh_io.h"

#include "test_tets.h"

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

std::string dir(const std::string& name) {
  const fs::path d = fs::path(outputDir()) / "separate" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

TetMesh shifted(TetMesh m, const Eigen::RowVector3d& by) {
  m.V.rowwise() += by;
  return m;
}

TEST(CliSeparate, WritesWhatTheLibraryComputesAndReportsTheOverlap) {
  const std::string in = dir("in"), out = dir("out") + "/meshes";
  const TetMesh a = boxTets(12, 6, 6, 2.0), b = shifted(a, {23.0, 0.7, 0.9});  // 1 mm overlap along x
  io::writeTetMesh(in + "/a.vtu", a);
  io::writeTetMesh(in + "/b.vtu", b);
  const std::string report = out + "/../report.json";
  const CommandResult r = runVesalius({"separate", "--mesh", in + "/a.vtu", "--mesh", in + "/b.vtu", "--out", out,
                                       "--report", report, "--progress", "none"});
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectContains(r.out, "b.vtu / a.vtu: ");

  std::vector<TetMesh> expected = {io::readTetMesh(in + "/a.vtu"), io::readTetMesh(in + "/b.vtu")};
  fit::removeInterpenetrations(expected);
  const TetMesh outA = io::readTetMesh(out + "/a.vtu"), outB = io::readTetMesh(out + "/b.vtu");
  EXPECT_EQ(outA.T, a.T);
  EXPECT_LT((outA.V - expected[0].V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((outB.V - expected[1].V).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((outA.V - a.V).rowwise().norm().maxCoeff(), 0.2);  // it did move the contact

  const nlohmann::json j = nlohmann::json::parse(std::ifstream(report));
  const nlohmann::json& pair = j["metrics"]["pair"];
  EXPECT_GT(pair["penetrating_vertices_before"].get<long>(), 0);
  EXPECT_EQ(pair["penetrating_vertices_after"].get<long>(), 0);
}

TEST(CliSeparate, RefusesBadInputWithOneLineAndWritesNothing) {
  const std::string in = dir("bad"), out = dir("bad-out") + "/meshes";
  io::writeTetMesh(in + "/a.vtu", boxTets(2, 2, 2));
  std::ofstream(in + "/broken.vtu") << "<VTKFile type=\"UnstructuredGrid\"";

  CommandResult r = runVesalius({"separate", "--mesh", in + "/a.vtu", "--out", out});
  EXPECT_EQ(r.exitCode, 2);
  expectContains(r.err, "at least two --mesh");

  r = runVesalius({"separate", "--mesh", in + "/a.vtu", "--mesh", in + "/broken.vtu", "--out", out});
  EXPECT_EQ(r.exitCode, 3);
  expectContains(r.err, "broken.vtu");
  EXPECT_FALSE(fs::exists(out + "/a.vtu"));

  r = runVesalius({"separate", "--mesh", in + "/a.vtu", "--mesh", in + "/a.vtu", "--out", out});
  EXPECT_EQ(r.exitCode, 2);
  expectContains(r.err, "same file name");

  io::writeTetMesh(in + "/b.vtu", boxTets(2, 2, 2));
  r = runVesalius({"separate", "--mesh", in + "/a.vtu", "--mesh", in + "/b.vtu", "--out", in, "--force"});
  EXPECT_EQ(r.exitCode, 2);
  expectContains(r.err, "is also an input");
}

}  // namespace
}  // namespace vesalius::test
