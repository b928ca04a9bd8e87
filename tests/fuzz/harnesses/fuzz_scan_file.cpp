#include "fuzz_file_common.h"
#include "vesalius/io/image_io.h"

#include <cmath>

// One harness per scan format (VESALIUS_FUZZ_EXTENSION: ".nrrd", ".mha", ".nii"): our header checks run
// first and ITK reads what they pass. A scan read must have valid geometry and as many voxels as it
// says, all finite.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzFile(
      data, size, std::string("fuzz") + VESALIUS_FUZZ_EXTENSION, [](const std::string& path) { return io::readScan(path); },
      [](const Image& scan, const std::string& path) {
        scan.geometry.validate(path);
        if (std::int64_t(scan.values.size()) != scan.geometry.voxelCount()) return false;
        for (float v : scan.values)
          if (!std::isfinite(v)) return false;
        return true;
      });
}
