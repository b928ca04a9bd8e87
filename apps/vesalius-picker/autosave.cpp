#include "autosave.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"

#include <filesystem>

namespace vesalius::picker {

std::string autosavePathFor(const std::string& outputPath) {
  const std::string extension = fileExtension(outputPath);
  const std::string stem = outputPath.substr(0, outputPath.size() - extension.size());
  return stem + ".autosave.mrk.json";
}

bool autosaveIsNewer(const std::string& autosavePath, const std::string& markersPath) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (!fs::exists(autosavePath, error)) return false;
  if (markersPath.empty() || !fs::exists(markersPath, error)) return true;
  return fs::last_write_time(autosavePath) > fs::last_write_time(markersPath);
}

RestorePolicy parseRestorePolicy(const std::string& text) {
  if (text == "yes") return RestorePolicy::Yes;
  if (text == "no") return RestorePolicy::No;
  if (text == "ask") return RestorePolicy::Ask;
  throw UsageError("--restore must be yes, no or ask, not '" + text + "'");
}

}  // namespace vesalius::picker
