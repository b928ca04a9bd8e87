#include "fuzz_common.h"
#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"

// A tag our CSV cannot carry (one holding a comma, or empty) is refused by the writer with a UsageError.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view text) { return io::parseMarkerCsv(text, "fuzz.csv", MarkerKind::Landmark); },
      [](const MarkerSet& s) {
        std::string text;
        try {
          text = io::formatMarkerCsv(s);
        } catch (const UsageError&) {
          return true;
        }
        const MarkerSet again = io::parseMarkerCsv(text, "roundtrip.csv", MarkerKind::Landmark);
        return again.markers.size() == s.markers.size();
      });
}
