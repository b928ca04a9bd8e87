#include "fuzz_common.h"
#include "vesalius/io/mesh_formats.h"

#include <limits>

// Binary or ASCII by the input's size, as the reader decides; whatever it reads must read back from both
// STL forms we write with its triangles (vertices are merged on read, so the count may only shrink).
// Binary STL stores float32: its writer refuses a coordinate beyond that range, and only such a one.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view bytes) { return io::parseStl(bytes, "fuzz.stl"); },
      [](const TriMesh& m) {
        const bool fitsFloat32 = m.V.size() == 0 || m.V.cwiseAbs().maxCoeff() <= std::numeric_limits<float>::max();
        std::vector<std::string> written{io::formatStlAscii(m)};
        try {
          written.push_back(io::formatStlBinary(m, "roundtrip.stl"));
          if (!fitsFloat32) return false;
        } catch (const BadInput&) {
          if (fitsFloat32) return false;
        }
        for (const std::string& bytes : written) {
          TriMesh again;
          try {
            again = io::parseStl(bytes, "roundtrip.stl");
          } catch (const BadInput&) {
            return false;
          }
          if (again.F.rows() != m.F.rows() || again.V.rows() > m.V.rows()) return false;
        }
        return true;
      });
}
