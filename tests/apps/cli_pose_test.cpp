// `vesalius rig` and `vesalius pose` end to end: MakeHuman's body rigged coarsely with its default skeleton
// (CoR centres of rotation included, the default), posed at one frame of the CMU motion by LBS, DQS and
// CoR. The posed skin keeps the input's topology, the posed skeleton its bone lengths, the volume changes
// stay within bounds, and the tet vertices of a bone move rigidly with it. Then the quality of every 25th
// frame of the whole motion (issue 6) by each method, from `pose --quality-only`'s quality.tsv, with the
// volume restored and the inverted or flat tets repaired (the defaults) and, for comparison, without the
// repair (--no-untangle) and without either (Sujar et al.'s bare skinning).
#include "run_command.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
constexpr int kFrame = 400;  // mid-motion: the CMU subject stands with the knees bent, arms moving
constexpr long kRigTets = 60000;

std::string dir(const std::string& name) {
  const fs::path d = fs::path(VESALIUS_TEST_OUTPUT) / "pose" / name;
  fs::remove_all(d);
  fs::create_directories(d.parent_path());
  return d.string();
}

// The coarse rig, made once by the one test below (ctest runs each TEST in its own process, in parallel,
// so tests sharing this directory would race).
const std::string& rigDir() {
  static const std::string d = [] {
    const std::string out = dir("rig");
    const CommandResult r = runVesalius({"rig", "--skin", kData + "/body/shapes/mh_neutral_body.obj", "--skeleton",
                                         kData + "/body/default.mhskel", "--base-mesh", kData + "/body/base.obj",
                                         "--voxel-size", "8", "--target-tets", std::to_string(kRigTets), "--out", out});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::cout << r.out;
    return out;
  }();
  return d;
}

// One pose at kFrame; `bare`: Sujar et al.'s skinning, without the volume restoration and the repair.
std::string pose(const std::string& method, bool bare = false) {
  const std::string out = dir(method + (bare ? "-bare" : ""));
  std::vector<std::string> args{"pose", "--anatomy", rigDir(), "--motion", kData + "/motion/01_01.bvh",
                                "--frame", std::to_string(kFrame), "--method", method, "--out", out};
  if (bare) args.insert(args.end(), {"--no-restore-volume", "--no-untangle"});
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out;
  return out;
}

std::vector<std::string> bones() {
  std::ifstream in(rigDir() + "/bones.txt");
  std::vector<std::string> names;
  for (std::string n; std::getline(in, n);) names.push_back(n);
  return names;
}

struct PoseChecks {
  double volumeChange = 0;      // posed skin volume / rest - 1
  double worstBoneLength = 0;   // mm
  double worstRigid = 0;        // mm, tet vertices with a bone weight > 0.999 against that bone's motion
  long rigidVertices = 0;
};

PoseChecks check(const std::string& out) {
  PoseChecks c;
  const TriMesh rest = io::readTriMesh(rigDir() + "/meshes/skin.obj");
  const TriMesh posed = io::readTriMesh(out + "/skin.obj");
  EXPECT_EQ(posed.F, rest.F);  // same topology
  EXPECT_EQ(posed.V.rows(), rest.V.rows());
  EXPECT_EQ(posed.UV.rows(), rest.UV.rows());
  c.volumeChange = enclosedVolume(posed.V, posed.F) / enclosedVolume(rest.V, rest.F) - 1;

  const Motion restSkeleton = io::readBvh(rigDir() + "/skeleton.bvh");
  const Motion posedSkeleton = io::readBvh(out + "/skeleton.bvh");
  const auto r = restSkeleton.worldPose(0), p = posedSkeleton.worldPose(0);
  for (std::size_t j = 0; j < r.size(); ++j) {
    const int parent = restSkeleton.skeleton.joints[j].parent;
    if (parent < 0) continue;
    c.worstBoneLength = std::max(c.worstBoneLength, std::abs((p[j].translation() - p[parent].translation()).norm() -
                                                             (r[j].translation() - r[parent].translation()).norm()));
  }
  const TetMesh restTets = io::readTetMesh(rigDir() + "/rig.vtu");
  const TetMesh posedTets = io::readTetMesh(out + "/tets.vtu");
  const Eigen::MatrixXd& W = restTets.vertexAttributes.real.at("weights");
  const std::vector<std::string> names = bones();
  for (Eigen::Index v = 0; v < W.rows(); ++v) {
    Eigen::Index b;
    if (W.row(v).maxCoeff(&b) < 0.999) continue;
    const int j = restSkeleton.skeleton.find(names[b]);
    const Eigen::Isometry3d motion = p[j] * r[j].inverse();
    const Eigen::Vector3d expected = motion * Eigen::Vector3d(restTets.V.row(v).transpose());
    c.worstRigid = std::max(c.worstRigid, (Eigen::Vector3d(posedTets.V.row(v).transpose()) - expected).norm());
    ++c.rigidVertices;
  }
  return c;
}

void expectRigOfTheMakeHumanBody() {
  const TetMesh tets = io::readTetMesh(rigDir() + "/rig.vtu");
  EXPECT_GE(tets.T.rows(), kRigTets / 2);  // within 2x of the target (issue 31)
  EXPECT_LE(tets.T.rows(), 2 * kRigTets);
  const Eigen::MatrixXd& W = tets.vertexAttributes.real.at("weights");
  EXPECT_EQ(W.cols(), Eigen::Index(bones().size()));
  EXPECT_GE(W.minCoeff(), 0.0);
  EXPECT_LE(W.maxCoeff(), 1.0);
  EXPECT_LT((W.rowwise().sum().array() - 1).abs().maxCoeff(), 1e-9);
  for (const char* bone : {"upperleg01.L", "lowerleg01.R", "upperarm01.L", "spine03", "head"})
    EXPECT_NE(std::find(bones().begin(), bones().end(), bone), bones().end()) << bone;
  // CoR centres by default: a vertex on one bone only is its own centre (rotation_centers.h).
  const Eigen::MatrixXd& centres = tets.vertexAttributes.real.at("cor_centre");
  const Eigen::VectorXi& bone = tets.vertexAttributes.integer.at("bone");
  ASSERT_EQ(centres.rows(), tets.V.rows());
  ASSERT_EQ(centres.cols(), 3);
  for (Eigen::Index v = 0; v < W.rows(); ++v) {
    if (bone[v] >= 0) {
      EXPECT_EQ(centres.row(v), tets.V.row(v)) << "bone vertex " << v;
    }
  }
}

void expectLbsDqsAndCorAtAFrameOfTheCmuMotion() {
  const PoseChecks lbs = check(pose("lbs")), dqs = check(pose("dqs")), cor = check(pose("cor"));
  const PoseChecks bareLbs = check(pose("lbs", true)), bareDqs = check(pose("dqs", true));
  std::printf("frame %d: skin volume change LBS %+.2f %%, DQS %+.2f %%, CoR %+.2f %% (bare skinning: LBS %+.2f %%, "
              "DQS %+.2f %%); bone lengths within %.2g mm; %ld rigid tet vertices within %.3g / %.3g / %.3g mm\n",
              kFrame, 100 * lbs.volumeChange, 100 * dqs.volumeChange, 100 * cor.volumeChange,
              100 * bareLbs.volumeChange, 100 * bareDqs.volumeChange, lbs.worstBoneLength, lbs.rigidVertices,
              lbs.worstRigid, dqs.worstRigid, cor.worstRigid);
  EXPECT_LT(lbs.worstBoneLength, 1e-6);
  EXPECT_LT(dqs.worstBoneLength, 1e-6);
  EXPECT_LT(cor.worstBoneLength, 1e-6);
  // Sujar et al.'s bare LBS collapses the bent elbows, knees and hips (measured -11.45 %); DQS keeps most of it
  // (measured -3.13 %: a crouch, one of the frames where bare skinning misses the issue's 3 %).
  EXPECT_LT(bareLbs.volumeChange, -0.05);
  EXPECT_LT(std::abs(bareDqs.volumeChange), std::abs(bareLbs.volumeChange) / 3);
  // With the volume restored (the default) every method keeps the skin within 1 % (measured LBS -0.25 %, DQS
  // -0.19 %, CoR -0.17 %).
  for (const PoseChecks* c : {&lbs, &dqs, &cor}) EXPECT_LT(std::abs(c->volumeChange), 0.01);
  // The bone vertices move rigidly with their bones, restored and repaired or not: retargeted skeleton ->
  // BVH -> skinning agree.
  EXPECT_GT(lbs.rigidVertices, 100);  // the bone vertices (169)
  for (const PoseChecks* c : {&lbs, &dqs, &cor, &bareLbs}) EXPECT_LT(c->worstRigid, 1e-6);
}

struct QualityRow {
  int frame = 0;
  long inverted = 0, leftOutside = 0, untangled = 0;
  double minVolumeRatio = 0, skinVolumeChangePct = 0, untangleMove = 0, tetVolumeChangePct = 0;
  std::string skinnedTetVolumeChangePct;  // "nan" with --no-restore-volume
  double restoreMove = 0;
};

std::vector<QualityRow> readQuality(const std::string& out, const std::string& method) {
  std::ifstream in(out + "/quality.tsv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "frame\tmethod\tinverted\tmin_volume_ratio\tskin_volume_change_pct\ttissue_vertices_left_outside"
                  "\tuntangled_tets\tuntangle_max_move_mm\ttet_volume_change_pct\tskinned_tet_volume_change_pct"
                  "\trestore_max_move_mm");
  std::vector<QualityRow> rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    QualityRow r;
    std::string m;
    fields >> r.frame >> m >> r.inverted >> r.minVolumeRatio >> r.skinVolumeChangePct >> r.leftOutside >> r.untangled >>
        r.untangleMove >> r.tetVolumeChangePct >> r.skinnedTetVolumeChangePct >> r.restoreMove;
    EXPECT_TRUE(fields && m == method) << line;
    rows.push_back(r);
  }
  return rows;
}

// What follows skinning: the volume restoration and the repair (the defaults), the restoration only, or
// neither (Sujar et al.'s bare skinning).
enum class AfterSkinning { restoreAndUntangle, restoreOnly, nothing };

// Every 25th frame of the whole CMU motion, quality only (no meshes written).
std::vector<QualityRow> qualityOverTheMotion(const std::string& method,
                                             AfterSkinning after = AfterSkinning::restoreAndUntangle) {
  const char* suffix[] = {"", "-tangled", "-bare"};
  const std::string out = dir("quality-" + method + suffix[int(after)]);
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::string> args{"pose", "--anatomy", rigDir(), "--motion", kData + "/motion/01_01.bvh", "--frames",
                                "0:2751", "--every", "25", "--quality-only", "--method", method, "--out", out};
  if (after != AfterSkinning::restoreAndUntangle) args.push_back("--no-untangle");
  if (after == AfterSkinning::nothing) args.push_back("--no-restore-volume");
  const CommandResult r = runVesalius(args);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  std::cout << r.out << method << ": "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  EXPECT_FALSE(fs::exists(out + "/frame_00000"));  // no meshes
  return readQuality(out, method);
}

struct Worst {
  long inverted = 0, framesInverted = 0, leftOutside = 0, untangled = 0;
  double minVolumeRatio = 1, skinVolumeChangePct = 0, untangleMove = 0;  // skin: largest |change|, signed
  double tetVolumeChangePct = 0;                                         // the whole tet mesh's, likewise
};

Worst worst(const std::vector<QualityRow>& rows, const std::vector<int>& skipFrames = {}) {
  Worst w;
  for (const QualityRow& r : rows) {
    if (std::find(skipFrames.begin(), skipFrames.end(), r.frame) != skipFrames.end()) continue;
    w.inverted = std::max(w.inverted, r.inverted);
    w.framesInverted += r.inverted > 0;
    w.leftOutside = std::max(w.leftOutside, r.leftOutside);
    w.minVolumeRatio = std::min(w.minVolumeRatio, r.minVolumeRatio);
    w.untangled = std::max(w.untangled, r.untangled);
    w.untangleMove = std::max(w.untangleMove, r.untangleMove);
    if (std::abs(r.skinVolumeChangePct) > std::abs(w.skinVolumeChangePct))
      w.skinVolumeChangePct = r.skinVolumeChangePct;
    if (std::abs(r.tetVolumeChangePct) > std::abs(w.tetVolumeChangePct)) w.tetVolumeChangePct = r.tetVolumeChangePct;
  }
  return w;
}

// The row of frame 400 against the posed files of a full pose at that frame, measured here independently.
void expectQualityOfFrame400AsMeasuredFromThePosedFiles(const std::vector<QualityRow>& cor) {
  const auto row = std::find_if(cor.begin(), cor.end(), [](const QualityRow& r) { return r.frame == kFrame; });
  ASSERT_NE(row, cor.end());
  const std::string out = pose("cor");
  const TetMesh rest = io::readTetMesh(rigDir() + "/rig.vtu"), posed = io::readTetMesh(out + "/tets.vtu");
  // The rest tets on the posed vertices: reading tets.vtu re-orients inverted tets (orientTetsPositively).
  const Eigen::ArrayXd ratio = tetVolumes(posed.V, rest.T).array() / tetVolumes(rest.V, rest.T).array();
  const TriMesh restSkin = io::readTriMesh(rigDir() + "/meshes/skin.obj");
  const TriMesh posedSkin = io::readTriMesh(out + "/skin.obj");
  EXPECT_EQ(row->inverted, (ratio <= 0).count());
  EXPECT_NEAR(row->minVolumeRatio, ratio.minCoeff(), 1e-6);
  EXPECT_NEAR(row->tetVolumeChangePct,
              100 * (tetVolumes(posed.V, rest.T).sum() / tetVolumes(rest.V, rest.T).sum() - 1), 1e-4);
  EXPECT_NEAR(row->skinVolumeChangePct,
              100 * (enclosedVolume(posedSkin.V, posedSkin.F) / enclosedVolume(restSkin.V, restSkin.F) - 1), 1e-4);
  EXPECT_EQ(readQuality(out, "cor").size(), 1u);  // a full pose writes its quality.tsv too
}

// CoR, the method that inverts most, with the volume restored but without the repair: every tet left inverted
// is one the repair takes (which also takes the flat ones, posed/rest volume below 0.05), and nothing is
// repaired with --no-untangle.
void expectTheRepairTakesEveryTetLeftInverted(const std::vector<QualityRow>& cor) {
  const std::vector<QualityRow> tangled = qualityOverTheMotion("cor", AfterSkinning::restoreOnly);
  ASSERT_EQ(tangled.size(), cor.size());
  long repaired = 0;
  for (std::size_t i = 0; i < cor.size(); ++i) {
    EXPECT_EQ(tangled[i].frame, cor[i].frame);
    EXPECT_EQ(tangled[i].untangled, 0);
    EXPECT_EQ(tangled[i].untangleMove, 0.0);
    EXPECT_EQ(tangled[i].restoreMove, cor[i].restoreMove);  // the same restoration, before the repair
    EXPECT_GE(cor[i].untangled, tangled[i].inverted) << "frame " << cor[i].frame;
    repaired += cor[i].untangled;
  }
  const Worst t = worst(tangled);
  std::printf("CoR restored, without the repair: worst %ld inverted tets (in %ld frames), smallest ratio %.3f, skin "
              "%+.2f %%; with it: %ld tets repaired in all\n", t.inverted, t.framesInverted, t.minVolumeRatio,
              t.skinVolumeChangePct, repaired);
  EXPECT_GT(t.inverted, 0);  // measured 72 (frame 1250; in 95 frames), bare CoR 67
}

// Sujar et al.'s bare skinning (neither restored nor repaired) against the default: the same skinning (the
// restored runs report the skinned tets' volume change before the restoration), and the skin volume it
// loses in the deepest crouches, beyond the issue's 3 %.
void expectBareSkinningLosesTheCrouches(const std::vector<QualityRow>& restored, const std::string& method) {
  const std::vector<QualityRow> bare = qualityOverTheMotion(method, AfterSkinning::nothing);
  ASSERT_EQ(bare.size(), restored.size());
  for (std::size_t i = 0; i < bare.size(); ++i) {
    EXPECT_EQ(bare[i].untangled + bare[i].restoreMove, 0);
    EXPECT_EQ(bare[i].skinnedTetVolumeChangePct, "nan");
    EXPECT_NEAR(std::stod(restored[i].skinnedTetVolumeChangePct), bare[i].tetVolumeChangePct, 1e-6);
  }
  const Worst w = worst(bare);
  const long beyond = std::count_if(bare.begin(), bare.end(), [](const QualityRow& r) {
    return std::abs(r.skinVolumeChangePct) > 3.0;
  });
  std::printf("%s bare: skin %+.2f %% at worst, %ld of %zu frames beyond 3 %%; %ld inverted tets at worst\n",
              method.c_str(), w.skinVolumeChangePct, beyond, bare.size(), w.inverted);
  EXPECT_LT(w.skinVolumeChangePct, -3.5);  // measured DQS -3.91 % (frame 200), CoR -4.40 % (1525)
  EXPECT_GE(beyond, 5);                    // measured 11 and 11 frames
}

void expectQualityOverTheCmuMotion() {
  const std::vector<QualityRow> lbs = qualityOverTheMotion("lbs"), dqs = qualityOverTheMotion("dqs"),
                                cor = qualityOverTheMotion("cor");
  for (const auto* rows : {&lbs, &dqs, &cor}) EXPECT_EQ(rows->size(), 111u);  // frames 0, 25, ..., 2750
  const Worst l = worst(lbs), d = worst(dqs), c = worst(cor);
  double restoreMove[3] = {0, 0, 0};
  for (int m = 0; m < 3; ++m)
    for (const QualityRow& r : *std::array{&lbs, &dqs, &cor}[std::size_t(m)])
      restoreMove[m] = std::max(restoreMove[m], r.restoreMove);
  std::printf("111 frames, restored and untangled: worst inverted tets LBS %ld (in %ld frames), DQS %ld (%ld), CoR "
              "%ld (%ld); smallest posed/rest tet volume %.3f / %.3f / %.3f; skin volume change %+.2f / %+.2f / "
              "%+.2f %% (tet mesh %+.2f / %+.2f / %+.2f %%); restoration moved vertices up to %.1f / %.1f / %.1f mm; "
              "most tets repaired in a frame %ld / %ld / %ld, vertices moved up to %.2f / %.2f / %.2f mm\n",
              l.inverted, l.framesInverted, d.inverted, d.framesInverted, c.inverted, c.framesInverted,
              l.minVolumeRatio, d.minVolumeRatio, c.minVolumeRatio, l.skinVolumeChangePct, d.skinVolumeChangePct,
              c.skinVolumeChangePct, l.tetVolumeChangePct, d.tetVolumeChangePct, c.tetVolumeChangePct,
              restoreMove[0], restoreMove[1], restoreMove[2], l.untangled, d.untangled, c.untangled, l.untangleMove,
              d.untangleMove, c.untangleMove);
  // Tissue vertices inside the rest tets stay inside their posed tets with every method, in every frame.
  EXPECT_EQ(l.leftOutside + d.leftOutside + c.leftOutside, 0);
  // No inverted or flat tet in any frame by any method (issue 6): every tet keeps at least 0.05 of its rest
  // volume (the repair's goal, posing/untangle_tets.h).
  EXPECT_EQ(l.inverted + d.inverted + c.inverted, 0);
  for (const Worst* w : {&l, &d, &c}) EXPECT_GE(w->minVolumeRatio, 0.05);
  // The restoration moves tissue by up to 43.3 / 22.4 / 27.4 mm (measured; the belly in the crouches), the
  // repair pushes folds back out of the joints by up to 26.5 / 36.3 / 33.8 mm.
  for (const double move : restoreMove) EXPECT_LT(move, 60.0);
  for (const Worst* w : {&l, &d, &c}) EXPECT_LT(w->untangleMove, 50.0);
  // The issue's 3 % for the posed skin holds in every frame by every method, LBS included, with the volume
  // restored (measured worst -0.46 / -0.38 / -0.51 %; the tet mesh -0.34 / -0.28 / -0.41 %). Bare skinning (below)
  // loses up to 3.91 % (DQS) and 4.40 % (CoR).
  for (const Worst* w : {&l, &d, &c}) EXPECT_LT(std::abs(w->skinVolumeChangePct), 1.0);
  expectQualityOfFrame400AsMeasuredFromThePosedFiles(cor);
  expectTheRepairTakesEveryTetLeftInverted(cor);
  expectBareSkinningLosesTheCrouches(dqs, "dqs");
  expectBareSkinningLosesTheCrouches(cor, "cor");
}

void expectABadEveryRefused() {
  const std::string motion = kData + "/motion/01_01.bvh";
  for (const std::vector<std::string>& frames : {std::vector<std::string>{"--frames", "0:100", "--every", "0"},
                                                 std::vector<std::string>{"--frames", "0:100", "--every", "-5"},
                                                 std::vector<std::string>{"--every", "5"}}) {
    const std::string out = dir("bad-every");
    std::vector<std::string> args{"pose", "--anatomy", rigDir(), "--motion", motion, "--quality-only", "--out", out};
    args.insert(args.end(), frames.begin(), frames.end());
    const CommandResult r = runVesalius(args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    expectContains(r.err, "--every");
    EXPECT_FALSE(fs::exists(out + "/quality.tsv"));
  }
}

void expectAnUnknownJointAngleRefused() {
  const std::string out = dir("bad");
  const CommandResult r = runVesalius({"pose", "--anatomy", rigDir(), "--angles", "thigh.L=30,0,0", "--out", out});
  EXPECT_EQ(r.exitCode, 2);
  expectContains(r.err, "no joint 'thigh.L'");
  EXPECT_FALSE(fs::exists(out + "/skin.obj"));
}

TEST(CliPose, RigsTheMakeHumanBodyAndPosesItAtAFrameOfTheCmuMotion) {
  {
    SCOPED_TRACE("rig");
    expectRigOfTheMakeHumanBody();
  }
  {
    SCOPED_TRACE("LBS, DQS and CoR");
    expectLbsDqsAndCorAtAFrameOfTheCmuMotion();
  }
  {
    SCOPED_TRACE("unknown joint");
    expectAnUnknownJointAngleRefused();
  }
  {
    SCOPED_TRACE("quality over the CMU motion");
    expectQualityOverTheCmuMotion();
  }
  {
    SCOPED_TRACE("bad --every");
    expectABadEveryRefused();
  }
}

}  // namespace
}  // namespace vesalius::test
