// A small file system of its own for tests of writers on a full disk (issue 32): a 2 MB tmpfs mounted per
// test, filled on demand. Without the right to mount one (root or CAP_SYS_ADMIN) the test is skipped.
#pragma once

#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace vesalius::test {

class FullDiskTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // A mount of its own per test: ctest runs the tests of a file at the same time.
    dir = std::filesystem::path(VESALIUS_TEST_OUTPUT) /
          ("tmpfs_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::system(("umount '" + dir.string() + "' 2>/dev/null").c_str());  // left by an aborted run
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    if (std::system(("mount -t tmpfs -o size=2m tmpfs '" + dir.string() + "' 2>/dev/null").c_str()) != 0)
      GTEST_SKIP() << "cannot mount a 2 MB tmpfs at " << dir.string()
                   << " (needs root or CAP_SYS_ADMIN): the full-disk cases are not run";
    mounted = true;
  }
  void TearDown() override {
    if (mounted) std::system(("umount '" + dir.string() + "'").c_str());
  }

  // Fills the file system but for about `leaveFree` bytes: a reserve of that size is written first and
  // removed once the filler has met ENOSPC.
  void fill(std::size_t leaveFree) {
    const std::string reserve = (dir / "reserve").string();
    if (leaveFree > 0) writeUntilFull(reserve, leaveFree);
    writeUntilFull((dir / "filler").string(), std::size_t(-1));
    if (leaveFree > 0) std::filesystem::remove(reserve);
  }

  static void writeUntilFull(const std::string& path, std::size_t limit) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    std::vector<char> block(4096, 'f');
    std::size_t written = 0;
    while (written < limit) {
      const ssize_t n = ::write(fd, block.data(), std::min(block.size(), limit - written));
      if (n <= 0) break;
      written += std::size_t(n);
    }
    ::close(fd);
  }

  // The names in the mounted folder, sorted.
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

  std::filesystem::path dir;
  bool mounted = false;
};

}  // namespace vesalius::test
