// BVH: the CMU and MakeHuman motions in testdata, exact round trips, and the bad files in testdata/bad.
#include "vesalius/core/error.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/text_file.h"

#include "expect_bad_input.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <sstream>

namespace vesalius::io {
namespace {

const std::string kData = VESALIUS_TESTDATA;

std::string outputPath(const std::string& name) {
  std::filesystem::create_directories(VESALIUS_TEST_OUTPUT);
  const std::string path = std::string(VESALIUS_TEST_OUTPUT) + "/" + name;
  std::filesystem::remove(path);
  return path;
}

int columns(const Motion& m) {
  int n = 0;
  for (const auto& c : m.channels) n += int(c.size());
  return n;
}

TEST(Bvh, CmuSubject01Trial01) {
  const Motion m = readBvh(kData + "/motion/01_01.bvh");
  const Skeleton& s = m.skeleton;
  ASSERT_EQ(s.joints.size(), 31u);  // ROOT + 30 JOINTs; the 7 End Sites are tails
  EXPECT_EQ(m.frameCount(), 2752);
  EXPECT_DOUBLE_EQ(m.frameTime, 0.0083333);
  EXPECT_EQ(columns(m), 96);
  EXPECT_EQ(m.values.cols(), 96);
  EXPECT_EQ(s.joints[0].name, "Hips");
  EXPECT_EQ(s.joints[0].parent, -1);
  ASSERT_EQ(m.channels[0].size(), 6u);
  EXPECT_EQ(m.channels[0][0], Channel::Xposition);
  EXPECT_EQ(m.channels[0][3], Channel::Zrotation);
  EXPECT_EQ(m.channels[0][5], Channel::Xrotation);
  const int upLeg = s.find("LeftUpLeg");
  ASSERT_GE(upLeg, 0);
  EXPECT_EQ(s.joints[std::size_t(s.joints[std::size_t(upLeg)].parent)].name, "LHipJoint");
  EXPECT_TRUE(
      s.joints[std::size_t(upLeg)].restLocal.translation().isApprox(Eigen::Vector3d(1.36306, -1.79463, 0.83929)));
  const Joint& toe = s.joints[std::size_t(s.find("LeftToeBase"))];
  EXPECT_TRUE(toe.tail.isApprox(Eigen::Vector3d(0, 0, 1.18966)));
  int tails = 0;
  for (const Joint& j : s.joints) tails += j.tail.isZero(0.0) ? 0 : 1;
  EXPECT_EQ(tails, 7);
  EXPECT_DOUBLE_EQ(m.values(0, 0), 9.3722);
  EXPECT_DOUBLE_EQ(m.values(0, 2), -17.3198);
  EXPECT_DOUBLE_EQ(m.values(2751, 0), 8.8787);
  EXPECT_DOUBLE_EQ(m.values(2751, 2), 38.5426);
  // The root's world position is its offset plus its position channels.
  EXPECT_TRUE(m.worldPose(0)[0].translation().isApprox(Eigen::Vector3d(9.3722, 17.8693, -17.3198)));
}

TEST(Bvh, MakeHumanPoses) {
  const Motion tpose = readBvh(kData + "/body/poses/tpose.bvh");
  EXPECT_EQ(tpose.skeleton.joints.size(), 173u);
  EXPECT_EQ(tpose.frameCount(), 1);
  EXPECT_DOUBLE_EQ(tpose.frameTime, 0.041667);
  EXPECT_EQ(tpose.skeleton.joints[0].name, "root");
  const Motion benchmark = readBvh(kData + "/body/poses/benchmark.bvh");
  EXPECT_EQ(benchmark.skeleton.joints.size(), 163u);
  EXPECT_EQ(benchmark.frameCount(), 1);
  EXPECT_EQ(benchmark.values.cols(), columns(benchmark));
}

void expectSameMotion(const Motion& a, const Motion& b) {
  ASSERT_EQ(a.skeleton.joints.size(), b.skeleton.joints.size());
  for (std::size_t j = 0; j < a.skeleton.joints.size(); ++j) {
    EXPECT_EQ(a.skeleton.joints[j].name, b.skeleton.joints[j].name);
    EXPECT_EQ(a.skeleton.joints[j].parent, b.skeleton.joints[j].parent);
    EXPECT_EQ(a.skeleton.joints[j].restLocal.translation(), b.skeleton.joints[j].restLocal.translation());
    EXPECT_EQ(a.skeleton.joints[j].tail, b.skeleton.joints[j].tail);
    EXPECT_EQ(a.channels[j], b.channels[j]);
  }
  EXPECT_EQ(a.frameTime, b.frameTime);
  ASSERT_EQ(a.values.rows(), b.values.rows());
  ASSERT_EQ(a.values.cols(), b.values.cols());
  EXPECT_EQ((a.values - b.values).cwiseAbs().maxCoeff(), 0.0);  // shortest round-trip digits: exact
}

TEST(Bvh, WriteThenReadGivesIdenticalMotion) {
  for (const char* file : {"/motion/01_01.bvh", "/body/poses/tpose.bvh", "/body/poses/benchmark.bvh"}) {
    SCOPED_TRACE(file);
    const Motion original = readBvh(kData + file);
    const std::string path = outputPath(std::filesystem::path(file).filename().string());
    writeBvh(path, original);
    expectSameMotion(original, readBvh(path));
    EXPECT_THROW(writeBvh(path, original), UsageError);  // an existing output is kept
    writeBvh(path, original, WriteOptions{true});
  }
}

TEST(Bvh, WriterOrdersJointsDepthFirstAndKeepsTheirValues) {
  Motion m;
  m.skeleton.joints = {{"root", -1, Eigen::Isometry3d::Identity(), Eigen::Vector3d::Zero()},
                       {"a", 0, Eigen::Isometry3d(Eigen::Translation3d(1, 0, 0)), Eigen::Vector3d::Zero()},
                       {"b", 0, Eigen::Isometry3d(Eigen::Translation3d(0, 1, 0)), Eigen::Vector3d(0, 0.5, 0)},
                       {"a1", 1, Eigen::Isometry3d(Eigen::Translation3d(0, 0, 1)), Eigen::Vector3d::Zero()}};
  m.channels = {{Channel::Yposition}, {Channel::Zrotation}, {Channel::Xrotation}, {Channel::Yrotation}};
  m.values.resize(1, 4);
  m.values << 10, 20, 30, 40;
  const Motion back = parseBvh(formatBvh(m), "memory");
  ASSERT_EQ(back.skeleton.joints.size(), 4u);
  EXPECT_EQ(back.skeleton.joints[2].name, "a1");  // depth first: root, a, a1, b
  EXPECT_EQ(back.skeleton.joints[3].name, "b");
  EXPECT_EQ(back.values(0, 2), 40);
  EXPECT_EQ(back.values(0, 3), 30);
  EXPECT_EQ(back.skeleton.joints[3].tail, Eigen::Vector3d(0, 0.5, 0));
  m.values.resize(1, 3);
  EXPECT_THROW(formatBvh(m), UsageError);
}

void expectBadInput(const std::string& file, const std::string& fragment) {
  const std::string path = kData + "/bad/" + file;
  test::expectOneLineBadInput(path, fragment, [&] { readBvh(path); });
}

TEST(Bvh, BadFilesAreOneLineBadInputWithLineNumbers) {
  expectBadInput("bvh_missing_channel.bvh", "line 20: frame 2 has 8 values, the hierarchy has 9 channels");
  expectBadInput("bvh_non_numeric.bvh", "line 20: bad value 'x'");
  expectBadInput("bvh_no_motion.bvh", "line 15: no MOTION section");
  expectBadInput("bvh_channels7.bvh", "line 9: CHANNELS 7");
  expectBadInput("bvh_unknown_channel.bvh", "line 9: unknown channel 'Wrotation'");
  expectBadInput("bvh_does_not_exist.bvh", "cannot open");
  EXPECT_THROW(parseBvh("", "empty"), BadInput);
}

// Exported motion whose frame lines disagree with its "Frames:" line is read, with one warning line: the
// declared count kept when there are more lines, the lines present when fewer. Made from the real CMU
// motion (one frame line repeated, three removed) and from the two small files in testdata/motion.
TEST(Bvh, MiscountedFrameListsAreReadWithOneWarning) {
  const std::string path = kData + "/motion/01_01.bvh";
  const std::string text = readTextFile(path);
  const Motion exact = parseBvh(text, path);
  std::string trimmed = text;
  while (!trimmed.empty() && (trimmed.back() == '\n' || trimmed.back() == '\r')) trimmed.pop_back();
  const std::string lastLine = trimmed.substr(trimmed.rfind('\n') + 1);

  std::string warning = "stale";
  const Motion extra = parseBvh(trimmed + "\n" + lastLine + "\n", "extra.bvh", &warning);
  std::cout << "one line more: " << warning << '\n';
  EXPECT_EQ(extra.frameCount(), 2752);
  EXPECT_EQ(extra.values, exact.values);
  EXPECT_NE(warning.find("extra.bvh: line "), std::string::npos) << warning;
  EXPECT_NE(warning.find("1 frame line beyond 'Frames: 2752' not read"), std::string::npos) << warning;
  EXPECT_EQ(warning.find('\n'), std::string::npos);

  std::string shorter = trimmed;
  for (int i = 0; i < 3; ++i) shorter.erase(shorter.rfind('\n'));
  const Motion fewer = parseBvh(shorter + "\n", "fewer.bvh", &warning);
  std::cout << "three lines fewer: " << warning << '\n';
  ASSERT_EQ(fewer.frameCount(), 2749);
  EXPECT_EQ(fewer.values, exact.values.topRows(2749));
  EXPECT_NE(warning.find("fewer.bvh: 2749 frame lines for 'Frames: 2752'; the 2749 present are read"), std::string::npos)
      << warning;

  parseBvh(text, path, &warning);
  EXPECT_TRUE(warning.empty()) << "an exact file gives no warning: " << warning;

  const Motion small = readBvh(kData + "/motion/bvh_extra_frame_line.bvh", &warning);
  EXPECT_EQ(small.frameCount(), 2);
  EXPECT_EQ(small.values(1, 8), 10);
  EXPECT_NE(warning.find("line 21: 1 frame line beyond 'Frames: 2' not read"), std::string::npos) << warning;
  EXPECT_EQ(readBvh(kData + "/motion/bvh_fewer_frame_lines.bvh", &warning).frameCount(), 2);
  EXPECT_NE(warning.find("2 frame lines for 'Frames: 3'"), std::string::npos) << warning;
  // A program's reading: the same warning as one line on the stream it gives; nothing for an exact file.
  std::ostringstream lines;
  EXPECT_EQ(readBvh(kData + "/motion/bvh_fewer_frame_lines.bvh", lines).frameCount(), 2);
  EXPECT_EQ(lines.str(), "warning: " + warning + "\n");
  std::ostringstream none;
  readBvh(path, none);
  EXPECT_EQ(none.str(), "");
  // A broken frame among the declared ones is still refused: the count of its values is not a miscount.
  EXPECT_THROW(parseBvh(shorter + "\n1 2 3\n", "broken.bvh"), BadInput);
}

}  // namespace
}  // namespace vesalius::io
