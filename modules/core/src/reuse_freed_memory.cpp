#include "vesalius/core/reuse_freed_memory.h"

#include <climits>  // also defines __GLIBC__ on glibc

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace vesalius {

void reuseFreedMemory() {
#if defined(__GLIBC__)
  static const bool applied = [] {
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);  // mallopt takes an int: the heap's top is trimmed above 2 GB only
    return true;
  }();
  (void)applied;
#endif
}

}  // namespace vesalius
