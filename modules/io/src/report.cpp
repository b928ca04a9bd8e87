#include "vesalius/io/report.h"

#include "vesalius/core/error.h"

#include <fstream>

namespace vesalius::io {

Report::Report(std::string command) {
  json_["command"] = std::move(command);
  json_["vesalius_version"] = VESALIUS_VERSION;
  json_["stages"] = nlohmann::json::array();
}

void Report::stage(const std::string& name, double seconds) {
  json_["stages"].push_back({{"name", name}, {"seconds", seconds}});
}

Report::StageTimer::StageTimer(Report& report, std::string name)
    : report_(report), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}

Report::StageTimer::~StageTimer() {
  report_.stage(name_, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

void Report::write(const std::string& path, const WriteOptions& options) const {
  const std::string text = json_.dump(2) + '\n';
  writeAtomically(path, options, [&](const std::string& temporary) { writeFileBytes(temporary, text); });
}

}  // namespace vesalius::io
