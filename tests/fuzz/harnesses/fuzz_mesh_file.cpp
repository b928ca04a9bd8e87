#include "fuzz_file_common.h"
#include "vesalius/io/mesh_io.h"

// One harness per VTK-read surface format (VESALIUS_FUZZ_EXTENSION: ".ply", ".vtp", ".vtk"): our checks
// run on what VTK reads. A mesh read must pass its own validation (finite coordinates, indices in range).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzFile(
      data, size, std::string("fuzz") + VESALIUS_FUZZ_EXTENSION, [](const std::string& path) { return io::readTriMesh(path); },
      [](const TriMesh& mesh, const std::string& path) {
        mesh.validate(path);
        return true;
      });
}
