#include "fuzz_common.h"
#include "vesalius/core/error.h"
#include "vesalius/io/marker_formats.h"

#include <Eigen/Geometry>

// ITK-SNAP annotations, read against an oblique scan geometry so that the voxel -> LPS mapping runs in
// full. A tag ITK-SNAP would cut (not one word without commas) is refused by the writer with a UsageError.
namespace {

vesalius::GridGeometry scanGeometry() {
  vesalius::GridGeometry g;
  g.size = {64, 48, 20};
  g.origin = {-120.5, 80.25, -300};
  g.spacing = {0.8, 0.8, 2.5};
  g.direction = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  return g;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  static const GridGeometry scan = scanGeometry();
  return fuzz::fuzzOne(
      data, size,
      [](std::string_view text) { return io::parseItkSnapAnnotations(text, "fuzz.annot", scan, MarkerKind::Landmark); },
      [](const MarkerSet& s) {
        std::string text;
        try {
          text = io::formatItkSnapAnnotations(s, scan);
        } catch (const UsageError&) {
          return true;
        }
        const MarkerSet again = io::parseItkSnapAnnotations(text, "roundtrip.annot", scan, MarkerKind::Landmark);
        return again.markers.size() == s.markers.size();
      });
}
