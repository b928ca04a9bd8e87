// The shipped data's folder (shipped_data.h).
#include "shipped_data.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace vesalius::cli {

std::string shippedShareDir() {
  namespace fs = std::filesystem;
  if (const char* dir = std::getenv("VESALIUS_SHARE_DIR"); dir && *dir) return dir;
  std::error_code error;
  // The program's own file, symbolic links resolved: PREFIX/bin/vesalius even when started through a link.
  const fs::path program = fs::canonical("/proc/self/exe", error);
  // VESALIUS_SHARE_FROM_BIN: the share folder relative to the program's folder, from CMake's install dirs.
  return (program.parent_path() / VESALIUS_SHARE_FROM_BIN).lexically_normal().string();
}

std::string shippedData(const std::string& relative) {
  return (std::filesystem::path(shippedShareDir()) / "data" / relative).string();
}

std::string shippedTemplates(const std::string& relative) {
  return (std::filesystem::path(shippedShareDir()) / "templates" / relative).string();
}

}  // namespace vesalius::cli
