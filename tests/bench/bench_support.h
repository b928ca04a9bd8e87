// What the benchmark drivers share: wall time of a piece of work, running a workload in a child process
// so that its peak resident memory is its own, timing a program run as a user would run it, and reading
// the JSON report it writes.
#pragma once

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

namespace vesalius::bench {

inline nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return nlohmann::json::parse(s.str());
}

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

// The 1-minute load average (0 if unreadable): printed beside timings on the shared machine.
inline double loadAverage() {
  double load = 0;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &load) != 1) load = 0;
    std::fclose(f);
  }
  return load;
}

// CPU time (user + system, all threads) of this process so far, in s: steadier than wall time on a loaded
// machine.
inline double cpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) + 1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// Minor page faults of this process so far: first touches of fresh memory, which cost about 20 µs each on
// the project's virtual machine.
inline long pageFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

struct ProgramRun {
  int exitCode = -1;
  double wall = 0, cpu = 0;  // s; CPU is user + system of the program and all its threads
  double peakMb = 0;
};

// Runs `program` with `args` (no shell), its standard output and error appended to `logPath`; waits for it.
inline ProgramRun runProgram(const std::string& program, const std::vector<std::string>& args, const std::string& logPath) {
  std::vector<char*> argv{const_cast<char*>(program.c_str())};  // built before fork: the child only execs
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::FILE* log = std::fopen(logPath.c_str(), "a");
  if (!log) return {};
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    std::fclose(log);
    return {};
  }
  if (pid == 0) {
    dup2(fileno(log), 1);
    dup2(fileno(log), 2);
    execv(program.c_str(), argv.data());
    _exit(127);
  }
  int status = 0;
  rusage usage{};
  wait4(pid, &status, 0, &usage);
  std::fclose(log);
  ProgramRun run;
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.cpu = usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  run.peakMb = double(usage.ru_maxrss) / 1024.0;
  return run;
}

}  // namespace vesalius::bench
