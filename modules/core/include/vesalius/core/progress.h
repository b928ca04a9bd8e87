// Progress of long work: a bar on a terminal, or the lines 3D Slicer reads from CLI modules.
//
// With Style::Slicer it prints, on standard output,
//   <filter-start><filter-name>NAME</filter-name><filter-comment>COMMENT</filter-comment></filter-start>
//   <filter-progress>0.42</filter-progress>
//   <filter-end><filter-name>NAME</filter-name><filter-time>1.2</filter-time></filter-end>
// as Slicer's CLI module protocol specifies. With Style::Bar it redraws one line on standard error
// (only when that is a terminal). Updates may come from several threads.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace vesalius {

class Progress {
 public:
  enum class Style { None, Bar, Slicer };

  // Parses "none", "bar", "slicer", or "auto" (Bar on a terminal, else None); throws UsageError.
  static Style parseStyle(const std::string& text);

  explicit Progress(Style style = Style::None);

  // Starts a named stage; fractions reported until the next begin() belong to it.
  void begin(const std::string& name, const std::string& comment = "");
  // Fraction of the current stage done, in [0, 1]. Cheap when the printed value would not change.
  void update(double fraction);
  void end();

  Style style() const { return style_; }

 private:
  Style style_;
  std::string name_;
  std::chrono::steady_clock::time_point start_;
  std::atomic<int> lastPermille_{-1};
  std::mutex printMutex_;
};

}  // namespace vesalius
