#include "fuzz_common.h"
#include "vesalius/io/makehuman_target.h"
#include "vesalius/io/mesh_formats.h"

#include <string>

// MakeHuman has no target writer here; the lines a target is made of are written back as MakeHuman writes
// them and must read back with every offset.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseMakeHumanTarget(text, "fuzz.target"); },
      [](const io::MakeHumanTarget& t) {
        if (t.vertex.rows() != t.offset.rows()) return false;
        std::string text;
        for (Eigen::Index k = 0; k < t.vertex.rows(); ++k) {
          io::detail::appendInteger(text, t.vertex(k));
          for (int a = 0; a < 3; ++a) {
            text += ' ';
            io::detail::appendReal(text, t.offset(k, a));
          }
          text += '\n';
        }
        const io::MakeHumanTarget again = io::parseMakeHumanTarget(text, "roundtrip.target");
        return again.vertex == t.vertex && again.offset == t.offset;
      });
}
