#include "run_command.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace vesalius::test {

namespace {
std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

CommandResult runVesalius(const std::vector<std::string>& args) {
  char outPath[] = "/tmp/vesalius-cli-outXXXXXX";
  char errPath[] = "/tmp/vesalius-cli-errXXXXXX";
  const int out = mkstemp(outPath), err = mkstemp(errPath);
  if (out < 0 || err < 0) throw std::runtime_error("mkstemp failed");
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(out, 1);
    dup2(err, 2);
    std::vector<char*> argv{const_cast<char*>(VESALIUS_EXE)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(VESALIUS_EXE, argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  close(out);
  close(err);
  CommandResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.out = slurp(outPath);
  r.err = slurp(errPath);
  std::remove(outPath);
  std::remove(errPath);
  return r;
}

std::string outputDir() {
  const std::string dir = VESALIUS_TEST_OUTPUT;
  std::filesystem::create_directories(dir);
  return dir;
}

void expectContains(const std::string& text, const std::string& fragment) {
  EXPECT_NE(text.find(fragment), std::string::npos) << "missing '" << fragment << "' in:\n" << text;
}

}  // namespace vesalius::test
