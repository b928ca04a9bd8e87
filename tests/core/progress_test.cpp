// Progress: the exact lines of 3D Slicer's CLI protocol, and silence where nothing should be printed.
#include "vesalius/core/error.h"
#include "vesalius/core/progress.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <unistd.h>

#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The text between `prefix` and `suffix` if `line` is exactly prefix + text + suffix.
bool between(const std::string& line, const std::string& prefix, const std::string& suffix,
             std::string& text) {
  if (line.size() < prefix.size() + suffix.size() || line.compare(0, prefix.size(), prefix) != 0 ||
      line.compare(line.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  text = line.substr(prefix.size(), line.size() - prefix.size() - suffix.size());
  return true;
}

// An end line for stage `name` whose time has the form "S.mmm".
bool isEndLine(const std::string& line, const std::string& name) {
  std::string time;
  if (!between(line, "<filter-end><filter-name>" + name + "</filter-name><filter-time>",
               "</filter-time></filter-end>", time))
    return false;
  const size_t dot = time.find('.');
  if (dot == std::string::npos || dot == 0 || time.size() - dot != 4) return false;
  for (size_t i = 0; i < time.size(); ++i)
    if (i != dot && !std::isdigit(static_cast<unsigned char>(time[i]))) return false;
  return true;
}

TEST(Progress, ParsesStyles) {
  EXPECT_EQ(Progress::parseStyle("none"), Progress::Style::None);
  EXPECT_EQ(Progress::parseStyle("bar"), Progress::Style::Bar);
  EXPECT_EQ(Progress::parseStyle("slicer"), Progress::Style::Slicer);
  EXPECT_EQ(Progress::parseStyle("auto"),
            isatty(STDERR_FILENO) ? Progress::Style::Bar : Progress::Style::None);
  EXPECT_THROW(Progress::parseStyle("fancy"), UsageError);
  EXPECT_THROW(Progress::parseStyle(""), UsageError);
  EXPECT_EQ(Progress(Progress::Style::Slicer).style(), Progress::Style::Slicer);
}

TEST(Progress, SlicerLinesAreExact) {
  Progress progress(Progress::Style::Slicer);
  testing::internal::CaptureStdout();
  progress.begin("Smoothing", "Taubin, 20 steps");
  progress.update(0.0);
  progress.update(0.0004);  // still 0 permille
  progress.update(0.42);
  progress.update(0.4201);  // still 420 permille
  progress.update(0.3);     // late report from a slower thread
  progress.update(0.4226);
  progress.update(1.0);
  progress.end();
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStdout());
  ASSERT_EQ(out.size(), 6u);
  EXPECT_EQ(out[0],
            "<filter-start><filter-name>Smoothing</filter-name>"
            "<filter-comment>Taubin, 20 steps</filter-comment></filter-start>");
  EXPECT_EQ(out[1], "<filter-progress>0</filter-progress>");
  EXPECT_EQ(out[2], "<filter-progress>0.42</filter-progress>");
  EXPECT_EQ(out[3], "<filter-progress>0.423</filter-progress>");
  EXPECT_EQ(out[4], "<filter-progress>1</filter-progress>");
  EXPECT_TRUE(isEndLine(out[5], "Smoothing")) << out[5];
}

TEST(Progress, EachStageStartsAgainFromZero) {
  Progress progress(Progress::Style::Slicer);
  testing::internal::CaptureStdout();
  progress.begin("first");
  progress.update(0.5);
  progress.end();
  progress.begin("a<b & c>d");
  progress.update(0.5);
  progress.update(7.0);  // clamped to 1
  progress.end();
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStdout());
  ASSERT_EQ(out.size(), 7u);
  EXPECT_EQ(out[0],
            "<filter-start><filter-name>first</filter-name><filter-comment></filter-comment>"
            "</filter-start>");
  EXPECT_EQ(out[1], "<filter-progress>0.5</filter-progress>");
  EXPECT_TRUE(isEndLine(out[2], "first")) << out[2];
  EXPECT_EQ(out[3],
            "<filter-start><filter-name>a&lt;b &amp; c&gt;d</filter-name><filter-comment>"
            "</filter-comment></filter-start>");
  EXPECT_EQ(out[4], "<filter-progress>0.5</filter-progress>");
  EXPECT_EQ(out[5], "<filter-progress>1</filter-progress>");
  EXPECT_TRUE(isEndLine(out[6], "a&lt;b &amp; c&gt;d")) << out[6];
}

TEST(Progress, ConcurrentUpdatesPrintIncreasingValuesOnce) {
  Progress progress(Progress::Style::Slicer);
  testing::internal::CaptureStdout();
  progress.begin("parallel");
  const int n = 100000;
  tbb::parallel_for(0, n + 1, [&](int i) { progress.update(double(i) / n); });
  progress.end();
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStdout());
  ASSERT_GE(out.size(), 3u);
  ASSERT_LE(out.size(), 1003u);
  double previous = -1.0;
  for (size_t i = 1; i + 1 < out.size(); ++i) {
    std::string text;
    ASSERT_TRUE(between(out[i], "<filter-progress>", "</filter-progress>", text)) << out[i];
    const double value = std::stod(text);
    EXPECT_GT(value, previous);
    previous = value;
  }
  EXPECT_EQ(out[out.size() - 2], "<filter-progress>1</filter-progress>");
}

TEST(Progress, NoneAndBarPrintNothingOffATerminal) {
  for (Progress::Style style : {Progress::Style::None, Progress::Style::Bar}) {
    Progress progress(style);
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();  // a captured stderr is a file, not a terminal
    progress.begin("quiet", "nothing to see");
    for (int i = 0; i <= 10; ++i) progress.update(i / 10.0);
    progress.end();
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  }
}

}  // namespace
}  // namespace vesalius
