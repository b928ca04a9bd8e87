// The full-body reference (MakeHuman's neutral body with Rajagopal's OpenSim bones), built once per test
// process by `vesalius reference full-body`, in a folder of the process's own (ctest runs test cases as
// processes at the same time). The including test defines VESALIUS_EXE, VESALIUS_TESTDATA and
// VESALIUS_TEST_OUTPUT.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/io/reference_anatomy_io.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace vesalius::test {

inline const ReferenceAnatomy& fullBodyReference() {
  static const ReferenceAnatomy reference = [] {
    namespace fs = std::filesystem;
    const std::string data = VESALIUS_TESTDATA;
    const fs::path out = fs::path(VESALIUS_TEST_OUTPUT) / ("full-body-" + std::to_string(getpid()));
    fs::remove_all(out);
    fs::create_directories(out.parent_path());
    const std::string command = std::string(VESALIUS_EXE) + " reference full-body --skin " + data +
                                "/body/shapes/mh_neutral_body.obj --skeleton " + data + "/body/default.mhskel --model " +
                                data + "/skeleton-opensim/Rajagopal2016.osim --out " + out.string() +
                                " --progress none > /dev/null";
    if (std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
    return io::readReferenceAnatomy(out.string());
  }();
  return reference;
}

}  // namespace vesalius::test
