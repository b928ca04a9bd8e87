#include "fuzz_common.h"
#include "vesalius/io/marker_formats.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseFcsv(text, "fuzz.fcsv", MarkerKind::Landmark); },
      [](const MarkerSet& s) {
        const MarkerSet again = io::parseFcsv(io::formatFcsv(s), "roundtrip.fcsv", MarkerKind::Landmark);
        return again.markers.size() == s.markers.size();
      });
}
