#include "vesalius/core/transparent_huge_pages.h"

#include <climits>  // also defines __GLIBC__ on glibc
#include <cstdlib>
#include <string>

#if defined(__GLIBC__) && defined(__linux__)
#include <unistd.h>
#endif

namespace vesalius {

void restartWithTransparentHugePages(char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
  constexpr const char* kTunable = "glibc.malloc.hugetlb";
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string value = tunables ? tunables : "";
  if (value.find(kTunable) != std::string::npos) return;
  value += std::string(value.empty() ? "" : ":") + kTunable + "=1";
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
#else
  (void)argv;
#endif
}

}  // namespace vesalius
