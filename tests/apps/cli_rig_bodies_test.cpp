// `vesalius rig` of MakeHuman bodies nobody tuned it on (issue 31): the three shipped shapes and bodies made
// here from MakeHuman's targets at their extremes (heavy and thin, young and old, both sexes), each rigged
// with the default skeleton and posed through the CMU motion 01_01 with CoR and the defaults (the volume
// restored, the tets repaired). Coarse for CI: 8 mm voxels, 20,000 tets asked, every 100th frame (28
// frames); the full-size runs (the default 4 mm and 100,000 tets, every frame) are a benchmark, not a test.
// For each body: `rig` exits 0; the tets within 2x of the target, both ways; the skeleton is the body's own
// (at least as many joints inside its skin as base.obj's); every capsule inside the meshed body
// (posing/bone_capsules.h: the joint's segment, trimmed at both ends) holds bone vertices; and over the
// motion no tissue vertex is left outside its tet, no tet inverted or flat, the skin within 3 % (issue 6,
// docs/methods/posing.md). Printed: tets, the rig's seconds, the worst inverted tets, the skin's volume
// change and the largest moves of the restoration and of the repair (issue 31 item 4 asks for them small).
#include "run_command.h"

#include "vesalius/core/skeleton.h"
#include "vesalius/core/tet_locator.h"
#include "vesalius/io/body_axes.h"
#include "vesalius/io/makehuman_target.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/skeleton_io.h"
#include "vesalius/meshing/winding_number.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kBody = std::string(VESALIUS_TESTDATA) + "/body/";
constexpr long kTargetTets = 20000;
constexpr int kEvery = 100;

struct Body {
  const char* name;
  const char* shape;                  // a shipped shape, or nullptr for the neutral body plus `targets`
  std::vector<const char*> targets;  // testdata/body/targets, each at weight 1
};

const Body kBodies[] = {
    {"neutral", "mh_neutral_body.obj", {}},
    {"male_young_thin", "mh_male_young_thin_body.obj", {}},
    {"male_young_muscular", "mh_male_young_muscular_body.obj", {}},
    {"female_young_heavy", nullptr, {"caucasian-female-young", "universal-female-young-maxmuscle-maxweight"}},
    {"female_young_thin", nullptr, {"caucasian-female-young", "universal-female-young-minmuscle-minweight"}},
    {"male_old_heavy", nullptr, {"caucasian-male-old", "universal-male-old-maxmuscle-maxweight"}},
    {"female_old_thin", nullptr, {"caucasian-female-old", "universal-female-old-minmuscle-minweight"}},
};

std::string folder(const std::string& name) {
  const fs::path d = fs::path(VESALIUS_TEST_OUTPUT) / "rig-bodies" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

// The body's skin in MakeHuman's space (as `rig` reads it).
TriMesh bodySkin(const Body& b) {
  if (b.shape) return io::readTriMesh(kBody + "shapes/" + b.shape);
  TriMesh skin = io::readTriMesh(kBody + "shapes/mh_neutral_body.obj");
  for (const char* t : b.targets)
    skin = io::applyMakeHumanTarget(skin, io::readMakeHumanTarget(kBody + "targets/" + t + ".target"));
  return skin;
}

// The joints of `s` inside `skin` (winding number above 1/2).
long jointsInside(const Skeleton& s, const TriMesh& skin) {
  const std::vector<Eigen::Isometry3d> rest = s.restWorld();
  MatrixX3d P(Eigen::Index(rest.size()), 3);
  for (std::size_t j = 0; j < rest.size(); ++j) P.row(Eigen::Index(j)) = rest[j].translation().transpose();
  const Eigen::VectorXd w = meshing::windingNumbers(skin.V, skin.F, P, meshing::WindingNumberOptions{0.0});
  return long((w.array() > 0.5).count());
}

struct Capsules {
  std::vector<std::string> inside;  // joints whose trimmed segment lies wholly in the rig's tets
  long outside = 0;                 // joints with a segment that leaves the tets (finger tips, the face)
};

// The joints with a segment (a tail) whose capsule axis, trimmed by BoneCapsuleOptions' default 15 % at both
// ends, lies in the tets: 16 points along it, each inside a tet.
Capsules capsulesInTets(const Skeleton& skeleton, const TetMesh& tets) {
  constexpr double kTrim = 0.15;
  constexpr int kSamples = 16;
  const TetLocator locator(tets.V, tets.T);
  const std::vector<Eigen::Isometry3d> rest = skeleton.restWorld();
  Capsules c;
  for (std::size_t j = 0; j < rest.size(); ++j) {
    if (skeleton.joints[j].tail.norm() == 0) continue;
    const Eigen::Vector3d head = rest[j].translation(), tail = rest[j] * skeleton.joints[j].tail;
    const Eigen::Vector3d a = head + kTrim * (tail - head), b = tail - kTrim * (tail - head);
    bool in = true;
    for (int k = 0; k < kSamples && in; ++k) in = bool(locator.locate(a + (b - a) * (k / double(kSamples - 1))));
    if (in)
      c.inside.push_back(skeleton.joints[j].name);
    else
      ++c.outside;
  }
  return c;
}

struct QualityWorst {
  int frames = 0;
  long inverted = 0, leftOutside = 0;
  double minVolumeRatio = 1, skinPct = 0, untangleMove = 0, restoreMove = 0;  // skinPct: largest |change|, signed
};

QualityWorst readQuality(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "frame\tmethod\tinverted\tmin_volume_ratio\tskin_volume_change_pct\ttissue_vertices_left_outside"
                  "\tuntangled_tets\tuntangle_max_move_mm\ttet_volume_change_pct\tskinned_tet_volume_change_pct"
                  "\trestore_max_move_mm");
  QualityWorst w;
  while (std::getline(in, line)) {
    std::istringstream f(line);
    int frame;
    long inverted, outside, untangled;
    double ratio, skin, untangleMove, tetPct, restoreMove;
    std::string method, skinnedPct;
    f >> frame >> method >> inverted >> ratio >> skin >> outside >> untangled >> untangleMove >> tetPct >> skinnedPct >>
        restoreMove;
    EXPECT_TRUE(f && method == "cor") << line;
    ++w.frames;
    w.inverted = std::max(w.inverted, inverted);
    w.leftOutside = std::max(w.leftOutside, outside);
    w.minVolumeRatio = std::min(w.minVolumeRatio, ratio);
    if (std::abs(skin) > std::abs(w.skinPct)) w.skinPct = skin;
    w.untangleMove = std::max(w.untangleMove, untangleMove);
    w.restoreMove = std::max(w.restoreMove, restoreMove);
  }
  return w;
}

class RigBodies : public ::testing::TestWithParam<Body> {};

TEST_P(RigBodies, RigsWithinTheBudgetWithEveryCapsuleHeldAndPosesThroughTheMotion) {
  const Body& b = GetParam();
  const std::string dir = folder(b.name);
  const TriMesh skin = bodySkin(b);
  const std::string skinFile = dir + "/skin.obj";
  io::writeTriMesh(skinFile, skin);

  // The body's own skeleton, as `rig` places it: its joints inside its skin (base.obj's would leave the
  // thin bodies' knees and the heavy bodies' shoulders).
  const TriMesh base = io::readTriMesh(kBody + "base.obj");
  const Skeleton own = io::readMakeHumanSkeletonOfBody(kBody + "default.mhskel", base, skin);
  const long ownInside = jointsInside(own, skin);
  const long baseInside = jointsInside(io::readMakeHumanSkeleton(kBody + "default.mhskel", base.V), skin);
  EXPECT_GE(ownInside, baseInside);

  const auto start = std::chrono::steady_clock::now();
  const CommandResult r = runVesalius({"rig", "--skin", skinFile, "--skeleton", kBody + "default.mhskel", "--base-mesh",
                                       kBody + "base.obj", "--voxel-size", "8", "--target-tets",
                                       std::to_string(kTargetTets), "--out", dir + "/rig", "--report",
                                       dir + "/rig.json", "--progress", "none"});
  const double rigSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir + "/rig.json"));
  const long tets = report["metrics"]["tets"];
  EXPECT_GE(tets, kTargetTets / 2);
  EXPECT_LE(tets, 2 * kTargetTets);

  // Every capsule whose axis lies in the rig's tets holds bone vertices: its joint is one of bones.txt's.
  const Capsules capsules =
      capsulesInTets(io::transformSkeleton(own, io::yUpToLps(), 100.0), io::readTetMesh(dir + "/rig/rig.vtu"));
  std::set<std::string> held;
  std::ifstream bonesFile(dir + "/rig/bones.txt");
  for (std::string line; std::getline(bonesFile, line);)
    if (!line.empty()) held.insert(line);
  std::string missing;
  for (const std::string& j : capsules.inside)
    if (!held.count(j)) missing += " " + j;
  EXPECT_TRUE(missing.empty()) << b.name << ": capsules in the tets without bone vertices:" << missing;

  const CommandResult p = runVesalius({"pose", "--anatomy", dir + "/rig", "--motion",
                                       std::string(VESALIUS_TESTDATA) + "/motion/01_01.bvh", "--frames", "0:2751",
                                       "--every", std::to_string(kEvery), "--quality-only", "--method", "cor", "--out",
                                       dir + "/pose", "--progress", "none"});
  ASSERT_EQ(p.exitCode, 0) << p.err;
  const QualityWorst w = readQuality(dir + "/pose/quality.tsv");
  std::printf("%s: %ld tets (%ld asked), rig %.1f s; joints inside the skin %ld (base.obj's %ld); %zu capsules in "
              "the tets, %zu bones; over %d frames: %ld inverted tets at worst, smallest volume ratio %.3f, skin "
              "%+.2f %%, %ld tissue vertices outside; moved up to %.1f mm by the restoration, %.1f mm by the "
              "repair\n",
              b.name, tets, kTargetTets, rigSeconds, ownInside, baseInside, capsules.inside.size(), held.size(),
              w.frames, w.inverted, w.minVolumeRatio, w.skinPct, w.leftOutside, w.restoreMove, w.untangleMove);
  EXPECT_EQ(w.frames, 2751 / kEvery + 1);
  // Issue 6's three claims (docs/methods/posing.md, "Quality over the whole motion"): tissue vertices stay in
  // their tets; no inverted or flat tet (each keeps 0.05 of its rest volume, the repair's goal); the posed
  // skin within 3 %.
  EXPECT_EQ(w.leftOutside, 0);
  EXPECT_EQ(w.inverted, 0);
  EXPECT_GE(w.minVolumeRatio, 0.05);
  EXPECT_LT(std::abs(w.skinPct), 3.0);
}

INSTANTIATE_TEST_SUITE_P(MakeHuman, RigBodies, ::testing::ValuesIn(kBodies),
                         [](const ::testing::TestParamInfo<Body>& i) { return std::string(i.param.name); });

}  // namespace
}  // namespace vesalius::test
