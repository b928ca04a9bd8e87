// TetGen meshes come as three files; the fuzz input holds them separated by NUL bytes: node \0 ele \0 face.
#include "fuzz_common.h"
#include "vesalius/io/mesh_formats.h"

#include <array>

namespace {
std::array<std::string_view, 3> splitFiles(std::string_view input) {
  std::array<std::string_view, 3> parts;
  for (std::size_t i = 0; i < 2; ++i) {
    const std::size_t end = input.find('\0');
    parts[i] = input.substr(0, end);
    input = end == std::string_view::npos ? std::string_view() : input.substr(end + 1);
  }
  parts[2] = input;
  return parts;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size,
      [](std::string_view input) {
        const auto files = splitFiles(input);
        return io::parseTetGen(files[0], files[1], files[2], "fuzz.node");
      },
      [](const TetMesh& m) {
        const io::TetGenFiles files = io::formatTetGen(m);
        const TetMesh again = io::parseTetGen(files.node, files.ele, files.face, "roundtrip.node");
        return again.V.rows() == m.V.rows() && again.T.rows() == m.T.rows();
      });
}
