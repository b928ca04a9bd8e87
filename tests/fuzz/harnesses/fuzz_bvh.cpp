#include "fuzz_common.h"
#include "vesalius/io/motion_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseBvh(text, "fuzz.bvh"); },
      [](const Motion& m) {
        const Motion again = io::parseBvh(io::formatBvh(m), "roundtrip.bvh");
        return again.skeleton.joints.size() == m.skeleton.joints.size() && again.values == m.values;
      });
}
