#include "common.h"

#include "vesalius/core/error.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>
#include <vector>

namespace vesalius::cli {

void CommonOptions::finish(const io::Report& report) const {
  if (!this->report.empty()) report.write(this->report, writeOptions());
}

namespace {

namespace fs = std::filesystem;

// The current command's input files, for messages from library code that knows no file name.
std::vector<std::string>& commandInputs() {
  static std::vector<std::string> inputs;
  return inputs;
}

// Output options are named so: --out, --out-*, --*-out, --png, --png-*, --*-png and --report. Every other
// option or argument whose value names an existing file or folder is an input.
bool isOutputOption(const std::string& name) {
  const auto endsWith = [&](const std::string& tail) {
    return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0;
  };
  return name == "--out" || name.rfind("--out-", 0) == 0 || endsWith("-out") || name == "--png" ||
         name.rfind("--png-", 0) == 0 || endsWith("-png") || name == "--report";
}

// The same file or folder: by device and inode when both exist, else by their normalised absolute paths.
bool samePath(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// Before any work: no output is an input (also through a symlink or a hard link), and no two outputs are
// one file. Inputs are also protected for the rest of the run (core/atomic_file.h), so that an output
// derived from another (a label table beside a label map, a mesh named after a label) cannot replace one.
void checkInputsAndOutputs(const CLI::App& command) {
  struct Named {
    std::string option, path;
  };
  std::vector<Named> inputs, outputs;
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0 || option->get_expected_max() == 0) continue;  // unset, or a flag
    const std::string name = option->get_name();
    for (const std::string& value : option->results()) {
      if (value.empty()) continue;
      std::error_code ec;
      if (isOutputOption(name))
        outputs.push_back({name, value});
      else if (fs::exists(value, ec))
        inputs.push_back({name, value});
    }
  }
  for (const Named& output : outputs) {
    // Said now, not when the first file is written after the work.
    struct stat info {};
    if (::stat(output.path.c_str(), &info) != 0 && errno == ENAMETOOLONG)
      throw UsageError(output.path + ": " + output.option + " names a path too long for the file system");
    std::error_code ec;
    const fs::path folder = fs::path(output.path).has_parent_path() ? fs::path(output.path).parent_path() : fs::path(".");
    if (fs::is_directory(folder, ec) && ::access(folder.c_str(), W_OK) != 0)
      throw UsageError(output.path + ": " + output.option + " is in the folder " + folder.string() +
                       ", which is not writable");
  }
  for (const Named& input : inputs) {
    protectInput(input.path);
    commandInputs().push_back(input.path);
  }
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    for (const Named& input : inputs)
      if (samePath(outputs[o].path, input.path))
        throw UsageError(outputs[o].path + ": " + outputs[o].option + " names the input " + input.option + " " +
                         input.path + "; an output never replaces an input, --force or not");
    for (std::size_t other = 0; other < o; ++other)
      if (samePath(outputs[o].path, outputs[other].path))
        throw UsageError(outputs[o].path + ": given to both " + outputs[other].option + " and " + outputs[o].option);
  }
}

}  // namespace

void addCommonOptions(CLI::App& command, CommonOptions& options) {
  command.add_option("--progress", options.progress, "Progress display: none, bar, slicer (3D Slicer CLI), auto")
      ->check(CLI::IsMember({"none", "bar", "slicer", "auto"}))
      ->capture_default_str();
  command.add_flag("--force", options.force, "Replace output files that already exist");
  command.add_option("--report", options.report, "Write a JSON report (inputs, parameters, stage times, metrics)");
  // Refused before the work, not after it: the report is written last.
  command.parse_complete_callback([&command, &options] {
    checkInputsAndOutputs(command);
    if (!options.report.empty() && !options.force && std::filesystem::exists(options.report))
      throw UsageError(options.report + ": exists; pass --force to replace it");
  });
}

std::string errorMessage(const Error& error) {
  const auto* badInput = dynamic_cast<const BadInput*>(&error);
  if (!badInput || !badInput->file().empty() || commandInputs().empty()) return error.what();
  std::string files;
  for (const std::string& input : commandInputs()) files += (files.empty() ? "" : ", ") + input;
  return files + ": " + badInput->problem();
}

Label resolveLabel(const LabelMap& map, const std::string& idOrName, const std::string& labelsPath) {
  try {
    return map.table.resolve(idOrName);
  } catch (const UsageError&) {
    throw UsageError(labelsPath + ": no label '" + idOrName + "' (neither an id nor a name in its label table)");
  }
}

}  // namespace vesalius::cli
