#include "fuzz_common.h"
#include "vesalius/io/marker_formats.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size,
      [](std::string_view text) { return io::parseSlicerMarkups(text, "fuzz.mrk.json", MarkerKind::Landmark); },
      [](const MarkerSet& s) {
        const MarkerSet again =
            io::parseSlicerMarkups(io::formatSlicerMarkups(s), "roundtrip.mrk.json", MarkerKind::Landmark);
        return again.markers.size() == s.markers.size();
      });
}
