// A program for transparent_huge_pages_test: restarts itself as the CLI does, fills 64 MB, and prints its
// GLIBC_TUNABLES, its first argument and the anonymous memory it holds in 2 MB pages (kB, from smaps_rollup).
#include "vesalius/core/transparent_huge_pages.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

int main(int argc, char** argv) {
  vesalius::restartWithTransparentHugePages(argv);
  constexpr std::size_t kBytes = std::size_t(64) << 20;
  char* block = static_cast<char*>(std::malloc(kBytes));
  if (!block) return 1;
  std::memset(block, 1, kBytes);
  long hugeKb = -1;
  std::ifstream rollup("/proc/self/smaps_rollup");
  for (std::string key; rollup >> key;)
    if (key == "AnonHugePages:") rollup >> hugeKb;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("%s\n%s\n%ld\n", tunables ? tunables : "", argc > 1 ? argv[1] : "", hugeKb);
  std::free(block);
  return 0;
}
