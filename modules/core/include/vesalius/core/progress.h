// Progress of long work: one bar over the whole command, on a terminal or as the lines 3D Slicer reads
// from CLI modules.
//
// A command's work is a sequence of stages (begin() ... end()); nested library pipelines begin stages of
// their own inside the command's. The overall fraction runs once from 0 to 1 over all of them:
//  - plan() gives the command's own stages their shares of the whole, by relative cost;
//  - a stage begun with a name the plan does not hold (a library's stage, or any stage without a plan)
//    takes half of what is left of the planned stage it runs in (of the whole, outside any), so the
//    bar never goes back and never reaches the end of its stage before that stage ends.
// With Style::Slicer it prints, on standard output, as Slicer's CLI module protocol specifies:
//   <filter-start><filter-name>NAME</filter-name><filter-comment>COMMENT</filter-comment></filter-start>
//   <filter-comment>NAME: COMMENT</filter-comment>        (each later stage)
//   <filter-progress>0.42</filter-progress>               (the whole command)
//   <filter-stage-progress>0.8</filter-stage-progress>    (the current stage)
//   <filter-end><filter-name>NAME</filter-name><filter-time>1.2</filter-time></filter-end>  (at destruction)
// With Style::Bar it redraws one line on standard error (only when that is a terminal): the current
// stage's name and the whole command's fraction. Updates may come from several threads.
#pragma once

#include <atomic>
#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace vesalius {

class Progress {
 public:
  enum class Style { None, Bar, Slicer };

  // Parses "none", "bar", "slicer", or "auto" (Bar on a terminal, else None); throws UsageError.
  static Style parseStyle(const std::string& text);

  explicit Progress(Style style = Style::None);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // The command's stages by begin()'s names with their relative costs (> 0), in order; their shares of
  // the whole are proportional to the costs. A planned stage that is skipped leaves its share unused.
  void plan(const std::vector<std::pair<std::string, double>>& stages);
  // Starts a named stage; fractions reported until the next begin() belong to it.
  void begin(const std::string& name, const std::string& comment = "");
  // Fraction of the current stage done, in [0, 1]. Cheap when the printed value would not change.
  void update(double fraction);
  // The current stage is done: the whole command's fraction moves to the stage's end.
  void end();

  Style style() const { return style_; }
  // The whole command's fraction shown last, in [0, 1].
  double overall() const { return std::max(0, shownPermille_.load()) / 1000.0; }

 private:
  struct Range {
    double lo = 0, hi = 1;
  };
  void show(int overallPermille, int stagePermille);

  Style style_;
  std::string firstName_, name_;
  std::chrono::steady_clock::time_point start_;
  std::map<std::string, Range> planned_;
  Range within_;  // the planned stage running, or the whole
  Range stage_;
  std::atomic<int> shownPermille_{-1}, stagePermille_{-1};
  std::mutex printMutex_;
  bool started_ = false, drawn_ = false;
};

}  // namespace vesalius
