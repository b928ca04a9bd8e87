// Shared by the harnesses of readers that take a path (the ITK- and VTK-backed ones, reference folders):
// each input is written to a file in a folder of this process and read from there. As in fuzz_common.h,
// the reader may refuse the file only with a vesalius::Error.
#pragma once

#include "vesalius/core/error.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace vesalius::fuzz {

// A folder of its own for this process, removed at exit; libFuzzer's workers are processes.
inline const std::filesystem::path& workFolder() {
  struct Folder {
    std::filesystem::path path;
    Folder() {
      path = std::filesystem::temp_directory_path() / ("vesalius-fuzz-" + std::to_string(::getpid()));
      std::filesystem::create_directories(path);
    }
    ~Folder() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Folder folder;
  return folder.path;
}

inline void writeBytes(const std::filesystem::path& path, const std::uint8_t* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out.flush()) __builtin_trap();  // the harness's own failure, not the reader's
}

// Writes the input to `name` in the work folder and calls read(path); a vesalius::Error is the refusal.
// What it reads must then pass check(result, path), which may throw a vesalius::Error too: that is a bug.
template <class Read, class Check>
int fuzzFile(const std::uint8_t* data, std::size_t size, const std::string& name, Read read, Check check) {
  const std::filesystem::path path = workFolder() / name;
  writeBytes(path, data, size);
  decltype(read(path.string())) result;
  try {
    result = read(path.string());
  } catch (const vesalius::Error&) {
    return 0;
  }
  try {
    if (!check(result, path.string())) __builtin_trap();
  } catch (const vesalius::Error&) {
    __builtin_trap();
  }
  return 0;
}

}  // namespace vesalius::fuzz
