#include "fuzz_file_common.h"
#include "vesalius/io/mesh_formats.h"
#include "vesalius/io/reference_anatomy_io.h"

#include <fstream>

// reference.json in a folder that holds the meshes the seeds name (skin.obj, tissues/bone.obj,
// tissues/liver.obj: octahedra); any other file it names is missing or outside the folder. A reference
// read must be written back by our writer and read again with the same tissues, points and cut vertices.
namespace {

namespace fs = std::filesystem;

vesalius::TriMesh octahedron(double radius) {
  vesalius::TriMesh m;
  m.V.resize(6, 3);
  m.V << radius, 0, 0, -radius, 0, 0, 0, radius, 0, 0, -radius, 0, 0, 0, radius, 0, 0, -radius;
  m.F.resize(8, 3);
  m.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
  return m;
}

const fs::path& referenceFolder() {
  static const fs::path folder = [] {
    const fs::path f = vesalius::fuzz::workFolder() / "reference";
    fs::create_directories(f / "tissues");
    const std::pair<const char*, double> meshes[] = {{"skin.obj", 60}, {"tissues/bone.obj", 20}, {"tissues/liver.obj", 30}};
    for (const auto& [file, radius] : meshes) std::ofstream(f / file) << vesalius::io::formatObj(octahedron(radius));
    return f;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  fuzz::writeBytes(referenceFolder() / "reference.json", data, size);
  ReferenceAnatomy anatomy;
  try {
    anatomy = io::readReferenceAnatomy(referenceFolder().string());
  } catch (const Error&) {
    return 0;
  }
  const fs::path copy = fuzz::workFolder() / "written";
  try {
    WriteOptions options;
    options.force = true;
    io::writeReferenceAnatomy(copy.string(), anatomy, options);
    const ReferenceAnatomy again = io::readReferenceAnatomy(copy.string());
    if (again.tissues.size() != anatomy.tissues.size() || again.points.size() != anatomy.points.size() ||
        again.skinCutVertices != anatomy.skinCutVertices || again.skin.V.rows() != anatomy.skin.V.rows())
      __builtin_trap();
  } catch (const BadInput& error) {
    // Two tissue names that become one file name: refusing them is right; anything else is a bug.
    if (error.problem().find("share the file name") == std::string::npos) __builtin_trap();
  }
  return 0;
}
