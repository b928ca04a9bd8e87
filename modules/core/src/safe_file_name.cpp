#include "vesalius/core/safe_file_name.h"

#include <cctype>

namespace vesalius {

std::string safeFileName(const std::string& name) {
  std::string file;
  for (const char c : name) {
    const unsigned char u = static_cast<unsigned char>(c);
    file += (u < 128 && std::isalnum(u)) || c == '-' || c == '_' ? c : '_';
  }
  return file.empty() ? "unnamed" : file;
}

}  // namespace vesalius
