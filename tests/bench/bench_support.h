// What the benchmark drivers share: wall time of a piece of work, and running a workload in a child
// process so that its peak resident memory is its own.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>

namespace vesalius::bench {

inline double seconds(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Runs `work` in a child process and appends " <peak> MB |" and a newline to the table row it printed.
// Exits with 1 if the child fails. The parent must not have started TBB's threads (forking is then safe).
inline void inChild(void (*work)()) {
  std::fflush(stdout);  // the child would print the parent's buffer again
  const pid_t pid = fork();
  if (pid == 0) {
    work();
    std::fflush(stdout);
    std::_Exit(0);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) std::exit(1);
  std::printf(" %.0f MB |\n", double(usage.ru_maxrss) / 1024.0);  // kilobytes on Linux
  std::fflush(stdout);
}

}  // namespace vesalius::bench
