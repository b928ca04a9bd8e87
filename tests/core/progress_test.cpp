// Progress: the exact lines of 3D Slicer's CLI protocol, and silence where nothing should be printed.
#include "vesalius/core/error.h"
#include "vesalius/core/progress.h"

#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <iostream>
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
  testing::internal::CaptureStdout();
  {
    Progress progress(Progress::Style::Slicer);
    progress.plan({{"Smoothing", 1}});
    progress.begin("Smoothing", "Taubin, 20 steps");
    progress.update(0.0);
    progress.update(0.0004);  // still 0 permille
    progress.update(0.42);
    progress.update(0.4201);  // still 420 permille
    progress.update(0.3);     // late report from a slower thread
    progress.update(0.4226);
    progress.update(1.0);
    progress.end();
  }
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStdout());
  ASSERT_EQ(out.size(), 10u);
  EXPECT_EQ(out[0],
            "<filter-start><filter-name>Smoothing</filter-name>"
            "<filter-comment>Taubin, 20 steps</filter-comment></filter-start>");
  EXPECT_EQ(out[1], "<filter-progress>0</filter-progress>");
  EXPECT_EQ(out[2], "<filter-stage-progress>0</filter-stage-progress>");
  EXPECT_EQ(out[3], "<filter-progress>0.42</filter-progress>");
  EXPECT_EQ(out[4], "<filter-stage-progress>0.42</filter-stage-progress>");
  EXPECT_EQ(out[5], "<filter-progress>0.423</filter-progress>");
  EXPECT_EQ(out[6], "<filter-stage-progress>0.423</filter-stage-progress>");
  EXPECT_EQ(out[7], "<filter-progress>1</filter-progress>");
  EXPECT_EQ(out[8], "<filter-stage-progress>1</filter-stage-progress>");
  EXPECT_TRUE(isEndLine(out[9], "Smoothing")) << out[9];
}

// The values of one tag, in order.
std::vector<double> values(const std::vector<std::string>& out, const std::string& tag) {
  std::vector<double> v;
  std::string text;
  for (const std::string& line : out)
    if (between(line, "<" + tag + ">", "</" + tag + ">", text)) v.push_back(std::stod(text));
  return v;
}

// One bar over the command: planned stages take their shares, a library's stages nested in one take
// halves of what is left of it, and the whole never goes back; one start line and one end line.
TEST(Progress, OneBarOverPlannedAndNestedStages) {
  testing::internal::CaptureStdout();
  double afterRead = 0, afterNested = 0;
  {
    Progress progress(Progress::Style::Slicer);
    progress.plan({{"read", 1}, {"build", 3}});
    progress.begin("read");
    progress.update(1.0);
    progress.end();
    afterRead = progress.overall();
    progress.begin("build", "a pipeline");
    progress.begin("surfaces");  // the pipeline's own stages
    progress.update(1.0);
    progress.end();
    progress.begin("a<b & c>d");
    progress.update(0.5);
    progress.update(7.0);  // clamped to 1
    afterNested = progress.overall();
    progress.begin("write");  // outside the plan, after it: half of what is left
    progress.update(1.0);
    progress.end();
  }
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStdout());
  std::cout << "overall after the first stage " << afterRead << ", after the nested stages " << afterNested << '\n';
  EXPECT_DOUBLE_EQ(afterRead, 0.25);
  // "surfaces" takes [0.25, 0.625], "a<b & c>d" [0.625, 0.8125] of "build"'s [0.25, 1].
  EXPECT_DOUBLE_EQ(afterNested, 0.813);
  ASSERT_GE(out.size(), 2u);
  EXPECT_EQ(out[0], "<filter-start><filter-name>read</filter-name><filter-comment></filter-comment></filter-start>");
  EXPECT_TRUE(isEndLine(out.back(), "read")) << out.back();
  long starts = 0, ends = 0;
  for (const std::string& line : out) starts += line.rfind("<filter-start>", 0) == 0, ends += line.rfind("<filter-end>", 0) == 0;
  EXPECT_EQ(starts, 1);
  EXPECT_EQ(ends, 1);
  EXPECT_NE(std::find(out.begin(), out.end(), "<filter-comment>build: a pipeline</filter-comment>"), out.end());
  EXPECT_NE(std::find(out.begin(), out.end(), "<filter-comment>a&lt;b &amp; c&gt;d</filter-comment>"), out.end());
  const std::vector<double> overall = values(out, "filter-progress");
  ASSERT_GE(overall.size(), 4u);
  for (std::size_t i = 1; i < overall.size(); ++i) EXPECT_GT(overall[i], overall[i - 1]);
  EXPECT_LT(overall.back(), 1.0);  // the last stage outside the plan leaves the end to the command's end
  EXPECT_THROW(Progress().plan({{"free", 0}}), UsageError);
}

TEST(Progress, ConcurrentUpdatesPrintIncreasingValuesOnce) {
  testing::internal::CaptureStdout();
  {
    Progress progress(Progress::Style::Slicer);
    progress.plan({{"parallel", 1}});
    progress.begin("parallel");
    const int n = 100000;
    tbb::parallel_for(0, n + 1, [&](int i) { progress.update(double(i) / n); });
    progress.end();
  }
  const std::vector<std::string> out = lines(testing::internal::GetCapturedStdout());
  const std::vector<double> stage = values(out, "filter-stage-progress"), overall = values(out, "filter-progress");
  ASSERT_GE(stage.size(), 1u);
  ASSERT_LE(stage.size(), 1001u);
  for (const std::vector<double>* v : {&stage, &overall})
    for (std::size_t i = 1; i < v->size(); ++i) EXPECT_GT((*v)[i], (*v)[i - 1]);
  EXPECT_EQ(stage.back(), 1.0);
  EXPECT_EQ(overall.back(), 1.0);
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
