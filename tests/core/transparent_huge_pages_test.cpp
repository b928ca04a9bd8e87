// restartWithTransparentHugePages: the program runs again with glibc.malloc.hugetlb=1 added to the
// tunables it was given, with the same arguments, and its large blocks then lie in 2 MB pages where the
// kernel offers them; a hugetlb setting the user gave is kept as it is.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace {

struct ProbeRun {
  std::string tunables, argument;
  long hugeKb = -1;
};

// Runs the probe through the shell with `environment` (e.g. "env -u GLIBC_TUNABLES").
ProbeRun runProbe(const std::string& environment) {
  const std::string command = environment + " " + HUGE_PAGES_PROBE + " 'an argument'";
  FILE* pipe = popen(command.c_str(), "r");
  EXPECT_NE(pipe, nullptr) << command;
  std::string output;
  std::array<char, 256> buffer{};
  while (pipe && std::fgets(buffer.data(), int(buffer.size()), pipe)) output += buffer.data();
  if (pipe) { EXPECT_EQ(pclose(pipe), 0) << command; }
  ProbeRun run;
  std::istringstream lines(output);
  std::getline(lines, run.tunables);
  std::getline(lines, run.argument);
  lines >> run.hugeKb;
  return run;
}

// The kernel's transparent_hugepage setting: "always", "madvise" (for memory that asks) or "never".
std::string kernelSetting() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  for (const char* setting : {"always", "madvise"})
    if (line.find(std::string("[") + setting + "]") != std::string::npos) return setting;
  return "never";
}

TEST(TransparentHugePages, TheProgramRunsAgainWithTheTunableAndItsArguments) {
  const ProbeRun run = runProbe("env -u GLIBC_TUNABLES");
  EXPECT_EQ(run.tunables, "glibc.malloc.hugetlb=1");
  EXPECT_EQ(run.argument, "an argument");
  if (kernelSetting() == "never") GTEST_SKIP() << "the kernel's transparent_hugepage setting is 'never'";
  EXPECT_GE(run.hugeKb, 32 * 1024);  // most of the 64 MB block
}

TEST(TransparentHugePages, OtherTunablesAreKeptAndTheUsersChoiceWins) {
  EXPECT_EQ(runProbe("GLIBC_TUNABLES=glibc.malloc.arena_max=2").tunables,
            "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1");
  const ProbeRun off = runProbe("GLIBC_TUNABLES=glibc.malloc.hugetlb=0");
  EXPECT_EQ(off.tunables, "glibc.malloc.hugetlb=0");
  EXPECT_EQ(off.argument, "an argument");
  if (kernelSetting() == "madvise") { EXPECT_LT(off.hugeKb, 32 * 1024); }  // nobody asked for huge pages
}

}  // namespace
