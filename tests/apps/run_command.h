// Runs the `vesalius` program as a user would and captures what it printed.
#pragma once

#include <string>
#include <vector>

namespace vesalius::test {

struct CommandResult {
  int exitCode = -1;
  std::string out, err;
};

// Runs VESALIUS_EXE with `args` (no shell: arguments are passed as they are).
CommandResult runVesalius(const std::vector<std::string>& args);

// This test program's output folder (VESALIUS_TEST_OUTPUT), created if missing.
std::string outputDir();

// A gtest failure showing `text` unless it contains `fragment`.
void expectContains(const std::string& text, const std::string& fragment);

}  // namespace vesalius::test
