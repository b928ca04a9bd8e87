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

}  // namespace

Progress::Style Progress::parseStyle(const std::string& text) {
  if (text == "none") return Style::None;
  if (text == "bar") return Style::Bar;
  if (text == "slicer") return Style::Slicer;
  if (text == "auto") return stderrIsTerminal() ? Style::Bar : Style::None;
  throw UsageError("unknown progress style '" + text + "' (use none, bar, slicer or auto)");
}

Progress::Progress(Style style) : style_(style), start_(std::chrono::steady_clock::now()) {}

void Progress::begin(const std::string& name, const std::string& comment) {
  std::lock_guard<std::mutex> lock(printMutex_);
  name_ = name;
  start_ = std::chrono::steady_clock::now();
  lastPermille_.store(-1);
  if (style_ != Style::Slicer) return;
  std::printf("<filter-start><filter-name>%s</filter-name><filter-comment>%s</filter-comment>"
              "</filter-start>\n",
              escapeXml(name).c_str(), escapeXml(comment).c_str());
  std::fflush(stdout);
}

void Progress::update(double fraction) {
  if (style_ == Style::None || !(fraction >= 0.0)) return;
  const int permille = int(std::lround(std::min(fraction, 1.0) * 1000.0));
  // Only increases are shown: updates from several threads may arrive out of order.
  if (permille <= lastPermille_.load(std::memory_order_relaxed)) return;
  std::lock_guard<std::mutex> lock(printMutex_);
  if (permille <= lastPermille_.load(std::memory_order_relaxed)) return;
  lastPermille_.store(permille, std::memory_order_relaxed);
  if (style_ == Style::Slicer) {
    std::printf("<filter-progress>%g</filter-progress>\n", permille / 1000.0);
    std::fflush(stdout);
  } else if (stderrIsTerminal()) {
    drawBar(name_, permille);
  }
}

void Progress::end() {
  std::lock_guard<std::mutex> lock(printMutex_);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (style_ == Style::Slicer) {
    std::printf("<filter-end><filter-name>%s</filter-name><filter-time>%.3f</filter-time>"
                "</filter-end>\n",
                escapeXml(name_).c_str(), seconds);
    std::fflush(stdout);
  } else if (style_ == Style::Bar && stderrIsTerminal()) {
    drawBar(name_, 1000);
    std::fputc('\n', stderr);
    std::fflush(stderr);
  }
  lastPermille_.store(-1);
}

}  // namespace vesalius
