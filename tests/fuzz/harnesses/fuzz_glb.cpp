#include "fuzz_common.h"
#include "vesalius/io/gltf.h"

#include <algorithm>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vesalius;
  return fuzz::fuzzOne(
      data, size, [](std::string_view bytes) { return io::parseGlb(bytes, "fuzz.glb"); },
      [](const std::vector<io::GltfMesh>& meshes) {
        std::vector<io::GltfNode> nodes;
        for (const io::GltfMesh& m : meshes) {
          io::GltfNode node{m.name, &m.mesh, m.rgba};
          for (double& c : node.rgba) c = std::clamp(c, 0.0, 1.0);  // any finite factor reads; we write 0..1
          nodes.push_back(node);
        }
        std::string bytes;
        try {
          bytes = io::formatGlb(nodes, "roundtrip.glb");
        } catch (const BadInput&) {
          return true;  // a transform took a coordinate beyond float32 metres: refusing it is right
        }
        const std::vector<io::GltfMesh> again = io::parseGlb(bytes, "roundtrip.glb");
        if (again.size() != meshes.size()) return false;
        for (std::size_t i = 0; i < again.size(); ++i)
          if (again[i].mesh.V.rows() != meshes[i].mesh.V.rows() || again[i].mesh.F != meshes[i].mesh.F) return false;
        return true;
      });
}
