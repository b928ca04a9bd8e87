#include "fuzz_common.h"
#include "vesalius/io/mesh_formats.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseObj(text, "fuzz.obj"); },
      [](const TriMesh& m) {
        const TriMesh again = io::parseObj(io::formatObj(m), "roundtrip.obj");
        return again.V.rows() == m.V.rows() && again.F.rows() == m.F.rows();
      });
}
