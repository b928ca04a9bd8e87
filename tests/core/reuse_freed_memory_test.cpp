// reuseFreedMemory: a block far above glibc's 32 MB mmap ceiling comes from the heap, and a block of the
// same size allocated after freeing it reuses the same memory (no new pages to fault in).
#include "vesalius/core/reuse_freed_memory.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace vesalius {
namespace {

#if defined(__GLIBC__)
TEST(ReuseFreedMemory, LargeBlocksComeFromTheHeapAndAreReused) {
  reuseFreedMemory();
  constexpr std::size_t kBytes = std::size_t(256) << 20;
  const std::size_t mappedBefore = mallinfo2().hblkhd;
  char* first = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(first, nullptr);
  std::memset(first, 1, kBytes);
  EXPECT_EQ(mallinfo2().hblkhd, mappedBefore);  // no mmapped block was added
  const auto firstAddress = reinterpret_cast<std::uintptr_t>(first);
  std::free(first);
  char* second = static_cast<char*>(std::malloc(kBytes));
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(second), firstAddress);
  std::free(second);
}
#endif

}  // namespace
}  // namespace vesalius
