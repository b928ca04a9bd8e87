#include "vesalius/core/atomic_file.h"

#include "vesalius/core/error.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

namespace vesalius {

namespace fs = std::filesystem;

std::string fileExtension(const std::string& path) {
  std::string name = fs::path(path).filename().string();
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::tolower(c); });
  for (const char* compound : {".nii.gz", ".mrk.json", ".seg.nrrd"}) {
    const std::string ext(compound);
    if (name.size() > ext.size() && name.compare(name.size() - ext.size(), ext.size(), ext) == 0) return ext;
  }
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos || dot == 0 ? std::string() : name.substr(dot);
}

void writeAtomically(const std::string& path, const WriteOptions& options,
                     const std::function<void(const std::string& temporaryPath)>& write) {
  const fs::path target(path);
  std::error_code ec;
  if (fs::exists(target, ec)) {
    // Renaming over a folder, device or pipe (say /dev/null) would destroy it, --force or not.
    if (!fs::is_regular_file(target, ec)) throw UsageError(path + ": exists and is not a regular file");
    if (!options.force) throw UsageError(path + ": exists; pass --force to replace it");
  }
  const fs::path parent = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(parent, ec)) throw UsageError(path + ": folder " + parent.string() + " does not exist");

  // Same folder, so the rename is atomic; same extension, so format-by-extension writers still work.
  const std::string ext = fileExtension(path);
  const fs::path temporary =
      parent / ("." + target.filename().string() + ".tmp" + std::to_string(::getpid()) + ext);
  try {
    write(temporary.string());
    fs::rename(temporary, target);
  } catch (...) {
    fs::remove(temporary, ec);
    throw;
  }
}

}  // namespace vesalius
