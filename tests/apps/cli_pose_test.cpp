// `vesalius rig` and `vesalius pose` end to end: MakeHuman's body rigged coarsely with its default skeleton
// (CoR centres of rotation included, the default), posed at one frame of the CMU motion by LBS, DQS and
// CoR. The posed skin keeps the input's topology, the posed skeleton its bone lengths, the volume changes
// stay within bounds, and the tet vertices of a bone move rigidly with it.
#include "run_command.h"

#include "vesalius/core/mesh_measures.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace vesalius::test {
namespace {

namespace fs = std::filesystem;

const std::string kData = VESALIUS_TESTDATA;
constexpr int kFrame = 400;  // mid-motion: the CMU subject stands with the knees bent, arms moving

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
                                         "--voxel-size", "8", "--target-tets", "15000", "--out", out});
    EXPECT_EQ(r.exitCode, 0) << r.err;
    std::cout << r.out;
    return out;
  }();
  return d;
}

std::string pose(const std::string& method) {
  const std::string out = dir(method);
  const CommandResult r = runVesalius({"pose", "--anatomy", rigDir(), "--motion", kData + "/motion/01_01.bvh",
                                       "--frame", std::to_string(kFrame), "--method", method, "--out", out});
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
  EXPECT_GT(tets.T.rows(), 40000);  // 73,921 measured (TetGen refines past the target)
  EXPECT_LT(tets.T.rows(), 150000);
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
  std::printf("frame %d: skin volume change LBS %+.2f %%, DQS %+.2f %%, CoR %+.2f %%; bone lengths within %.2g mm; "
              "%ld rigid tet vertices within %.3g / %.3g / %.3g mm\n",
              kFrame, 100 * lbs.volumeChange, 100 * dqs.volumeChange, 100 * cor.volumeChange, lbs.worstBoneLength,
              lbs.rigidVertices, lbs.worstRigid, dqs.worstRigid, cor.worstRigid);
  EXPECT_LT(lbs.worstBoneLength, 1e-6);
  EXPECT_LT(dqs.worstBoneLength, 1e-6);
  // LBS collapses the bent elbows, knees and hips (measured -13.8 %); DQS keeps volume within the 3 % the
  // issue asks of the posed skin (measured -1.1 %).
  EXPECT_LT(lbs.volumeChange, -0.05);
  EXPECT_LT(std::abs(dqs.volumeChange), 0.03);
  EXPECT_LT(std::abs(dqs.volumeChange), std::abs(lbs.volumeChange) / 5);
  EXPECT_GT(lbs.rigidVertices, 100);  // the bone vertices (139): retargeted skeleton -> BVH -> skinning agree
  EXPECT_LT(lbs.worstRigid, 1e-6);
  EXPECT_LT(dqs.worstRigid, 1e-6);
  // CoR on the default rig keeps the volume LBS loses (measured -1.60 % against -13.75 %).
  EXPECT_LT(std::abs(cor.volumeChange), 0.03);
  EXPECT_LT(std::abs(cor.volumeChange), std::abs(lbs.volumeChange) / 4);
  EXPECT_LT(cor.worstBoneLength, 1e-6);
  EXPECT_LT(cor.worstRigid, 1e-6);
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
}

}  // namespace
}  // namespace vesalius::test
