#include "fuzz_common.h"
#include "vesalius/io/mesh_formats.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseGmsh(text, "fuzz.msh"); },
      [](const TetMesh& m) {
        const TetMesh again = io::parseGmsh(io::formatGmsh(m), "roundtrip.msh");
        return again.V.rows() == m.V.rows() && again.T.rows() == m.T.rows() && again.F.rows() == m.F.rows();
      });
}
