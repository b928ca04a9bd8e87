// The wall time of a pipeline's stages, in the order they ran: each end() closes the stage that began at
// the previous one (or at construction), for the stage times a report lists.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace vesalius {

class StageClock {
 public:
  explicit StageClock(std::vector<std::pair<std::string, double>>& stages) : stages_(stages) {}
  void end(const std::string& stage) {
    const auto now = std::chrono::steady_clock::now();
    stages_.emplace_back(stage, std::chrono::duration<double>(now - start_).count());
    start_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& stages_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace vesalius
