#include "fuzz_file_common.h"
#include "vesalius/io/mesh_io.h"

// One harness per VTK-read tet mesh format (VESALIUS_FUZZ_EXTENSION: ".vtu", ".vtk"): our walk of the
// legacy file, then VTK, then our checks on the cells it read. A tet mesh read must pass its own
// validation (finite coordinates, four indices in range per tet).
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzFile(
      data, size, std::string("fuzz") + VESALIUS_FUZZ_EXTENSION, [](const std::string& path) { return io::readTetMesh(path); },
      [](const TetMesh& mesh, const std::string& path) {
        mesh.validate(path);
        return true;
      });
}
