// The JSON report every command can write with --report (DESIGN.md, "Progress and reports"):
// what went in, the parameters, how long each stage took, and the numbers that tell how it went.
//
//   {"command": "segment", "vesalius_version": "0.1.0",
//    "inputs": {"scan": "ct.nii.gz"}, "parameters": {...}, "outputs": {...},
//    "stages": [{"name": "body mask", "seconds": 0.41}, ...], "metrics": {...}}
#pragma once

#include "vesalius/core/atomic_file.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <string>

namespace vesalius::io {

class Report {
 public:
  explicit Report(std::string command);

  void input(const std::string& name, const std::string& path) { json_["inputs"][name] = path; }
  void output(const std::string& name, const std::string& path) { json_["outputs"][name] = path; }
  void parameter(const std::string& name, const nlohmann::json& value) { json_["parameters"][name] = value; }
  void metric(const std::string& name, const nlohmann::json& value) { json_["metrics"][name] = value; }
  void stage(const std::string& name, double seconds);

  // Times a stage from construction to destruction.
  class StageTimer {
   public:
    StageTimer(Report& report, std::string name);
    ~StageTimer();
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

   private:
    Report& report_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
  };
  StageTimer time(const std::string& name) { return StageTimer(*this, name); }

  const nlohmann::json& json() const { return json_; }
  // Pretty-printed, written atomically.
  void write(const std::string& path, const WriteOptions& options) const;

 private:
  nlohmann::json json_;
};

}  // namespace vesalius::io
