// Progress reporting: a terminal bar, or the XML-like lines of 3D Slicer's CLI module protocol
// (Slicer "Execution Model", section "Showing Progress in an Application").
#include "vesalius/core/progress.h"

#include "vesalius/core/error.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesalius {
namespace {

constexpr int kBarWidth = 30;

// Slicer parses the lines as XML, so a name such as "a<b" must not break them.
std::string escapeXml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      default: out += c;
    }
  }
  return out;
}

bool stderrIsTerminal() { return isatty(STDERR_FILENO) == 1; }

void drawBar(const std::string& name, int permille) {
  const int filled = permille * kBarWidth / 1000;
  std::fprintf(stderr, "\r%s [%s%s] %5.1f%%\033[K", name.c_str(), std::string(filled, '#').c_str(),
               std::string(kBarWidth - filled, ' ').c_str(), permille / 10.0);
  std::fflush(stderr);
}

int permilleOf(double fraction) { return int(std::lround(std::clamp(fraction, 0.0, 1.0) * 1000.0)); }

}  // namespace

Progress::Style Progress::parseStyle(const std::string& text) {
  if (text == "none") return Style::None;
  if (text == "bar") return Style::Bar;
  if (text == "slicer") return Style::Slicer;
  if (text == "auto") return stderrIsTerminal() ? Style::Bar : Style::None;
  throw UsageError("unknown progress style '" + text + "' (use none, bar, slicer or auto)");
}

Progress::Progress(Style style) : style_(style), start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() {
  std::lock_guard<std::mutex> lock(printMutex_);
  if (style_ == Style::Slicer && started_) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::printf("<filter-end><filter-name>%s</filter-name><filter-time>%.3f</filter-time></filter-end>\n",
                escapeXml(firstName_).c_str(), seconds);
    std::fflush(stdout);
  } else if (drawn_) {
    std::fputc('\n', stderr);
    std::fflush(stderr);
  }
}

void Progress::plan(const std::vector<std::pair<std::string, double>>& stages) {
  double total = 0;
  for (const auto& [name, cost] : stages) {
    if (!(cost > 0) || !std::isfinite(cost)) throw UsageError("progress plan: stage '" + name + "' has no cost");
    total += cost;
  }
  std::lock_guard<std::mutex> lock(printMutex_);
  planned_.clear();
  double lo = 0;
  for (const auto& [name, cost] : stages) {
    planned_[name] = {lo, std::min(1.0, lo + cost / total)};
    lo += cost / total;
  }
}

void Progress::begin(const std::string& name, const std::string& comment) {
  std::lock_guard<std::mutex> lock(printMutex_);
  name_ = name;
  const double now = std::max(0, shownPermille_.load()) / 1000.0;
  if (const auto found = planned_.find(name); found != planned_.end()) {
    within_ = found->second;
    stage_ = within_;
  } else {
    const double lo = std::clamp(now, within_.lo, within_.hi);
    stage_ = {lo, lo + (within_.hi - lo) / 2};
  }
  stagePermille_.store(-1);
  if (style_ != Style::Slicer) return;
  if (!started_) {
    started_ = true;
    firstName_ = name;
    std::printf("<filter-start><filter-name>%s</filter-name><filter-comment>%s</filter-comment></filter-start>\n",
                escapeXml(name).c_str(), escapeXml(comment).c_str());
  } else {
    std::printf("<filter-comment>%s%s%s</filter-comment>\n", escapeXml(name).c_str(), comment.empty() ? "" : ": ",
                escapeXml(comment).c_str());
  }
  std::fflush(stdout);
}

void Progress::update(double fraction) {
  if (style_ == Style::None || !(fraction >= 0.0)) return;
  const int stage = permilleOf(fraction);
  // Only increases are shown: updates from several threads may arrive out of order.
  if (stage <= stagePermille_.load(std::memory_order_relaxed)) return;
  std::lock_guard<std::mutex> lock(printMutex_);
  if (stage <= stagePermille_.load(std::memory_order_relaxed)) return;
  stagePermille_.store(stage, std::memory_order_relaxed);
  show(permilleOf(stage_.lo + (stage_.hi - stage_.lo) * stage / 1000.0), stage);
}

void Progress::end() {
  std::lock_guard<std::mutex> lock(printMutex_);
  if (style_ != Style::None && stagePermille_.load() < 1000) show(permilleOf(stage_.hi), 1000);
  stagePermille_.store(1000);
  shownPermille_.store(std::max(shownPermille_.load(), permilleOf(stage_.hi)));
  // After a planned stage, a stage outside the plan shares what is left of the whole.
  if (planned_.count(name_)) within_ = Range{};
}

// Called with printMutex_ held.
void Progress::show(int overallPermille, int stagePermille) {
  const bool moved = overallPermille > shownPermille_.load();
  if (moved) shownPermille_.store(overallPermille);
  if (style_ == Style::Slicer) {
    if (moved) std::printf("<filter-progress>%g</filter-progress>\n", overallPermille / 1000.0);
    std::printf("<filter-stage-progress>%g</filter-stage-progress>\n", stagePermille / 1000.0);
    std::fflush(stdout);
  } else if (style_ == Style::Bar && stderrIsTerminal()) {
    drawBar(name_, std::max(0, shownPermille_.load()));
    drawn_ = true;
  }
}

}  // namespace vesalius
