#include "common.h"

#include "vesalius/core/error.h"

#include <filesystem>

namespace vesalius::cli {

void CommonOptions::finish(const io::Report& report) const {
  if (!this->report.empty()) report.write(this->report, writeOptions());
}

void addCommonOptions(CLI::App& command, CommonOptions& options) {
  command.add_option("--progress", options.progress, "Progress display: none, bar, slicer (3D Slicer CLI), auto")
      ->check(CLI::IsMember({"none", "bar", "slicer", "auto"}))
      ->capture_default_str();
  command.add_flag("--force", options.force, "Replace output files that already exist");
  command.add_option("--report", options.report, "Write a JSON report (inputs, parameters, stage times, metrics)");
  // Refused before the work, not after it: the report is written last.
  command.parse_complete_callback([&options] {
    if (!options.report.empty() && !options.force && std::filesystem::exists(options.report))
      throw UsageError(options.report + ": exists; pass --force to replace it");
  });
}

Label resolveLabel(const LabelMap& map, const std::string& idOrName, const std::string& labelsPath) {
  try {
    return map.table.resolve(idOrName);
  } catch (const UsageError&) {
    throw UsageError(labelsPath + ": no label '" + idOrName + "' (neither an id nor a name in its label table)");
  }
}

}  // namespace vesalius::cli
