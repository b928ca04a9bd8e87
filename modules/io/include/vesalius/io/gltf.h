// Binary glTF 2.0 (.glb) models: several named, coloured surfaces in one file that web viewers, game
// engines and VR tools open (Khronos, "glTF 2.0 Specification", https://registry.khronos.org/glTF/specs/2.0/).
//
// What is written (spec §4.4 GLB layout; §3.7 geometry; §3.9 materials):
//   - a 12-byte header, one JSON chunk padded with spaces and one BIN chunk padded with zeros, both to 4
//     bytes; one buffer (the BIN chunk); every bufferView starts on a 4-byte boundary;
//   - one node per GltfNode, named by it, in scene 0, with no transform; each node has its own mesh of one
//     triangle primitive (mode 4): POSITION (float32 VEC3, with the min/max §3.7.2.1 requires), NORMAL
//     (float32 VEC3, unit, area-weighted per vertex so viewers shade smoothly) and uint32 indices;
//   - one material per node: pbrMetallicRoughness baseColorFactor = rgba, metallicFactor 0,
//     roughnessFactor 0.6, doubleSided false, alphaMode BLEND when alpha < 1 (else OPAQUE);
//   - asset.generator "Vesalius".
// uv and attributes are not written.
//
// Axes and units (spec §3.4: +Y up, +Z the front of an asset, right-handed, metres). From our LPS
// millimetres, a rotation (winding and handedness kept) and a scale of 0.001:
//   glTF x = L / 1000    (the patient's left; -X is the asset's right as the spec has it)
//   glTF y = S / 1000    (up: the patient stands along +Y)
//   glTF z = -P / 1000   (anterior: the patient faces +Z)
// so a point at L = 10 mm is at glTF (0.01, 0, 0). Positions are float32, so a round trip keeps a
// coordinate to float32 rounding of its value in metres (about 0.03 µm at 0.5 m).
//
// The reader takes what this writer writes and what other tools commonly write for triangle surfaces:
// the nodes of the default scene (or of every root node when there is no scene) with their transforms
// (matrix or TRS, composed down the node tree) applied; primitives of mode 4 (or no mode), float32
// POSITION, uint8/uint16/uint32 indices or none; several primitives of a mesh are concatenated. The
// colour is the first primitive's material baseColorFactor (white without one). Anything else (other
// modes, external or data-URI buffers, sparse or quantized accessors, Draco) is a one-line BadInput naming
// the file. Every offset, length and index is checked against the buffer before it is used, and no
// allocation is larger than a small multiple of the file size.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace vesalius::io {

// One node to write: `mesh` (mm, LPS; not owned, must outlive the call) with at least one triangle.
struct GltfNode {
  std::string name;
  const TriMesh* mesh = nullptr;
  std::array<double, 4> rgba{1, 1, 1, 1};  // linear 0..1, as glTF's baseColorFactor
};

// One node read back: its mesh in mm LPS (V, F only), validated.
struct GltfMesh {
  std::string name;
  TriMesh mesh;
  std::array<double, 4> rgba{1, 1, 1, 1};
};

// The axis map above, one point: mm LPS -> glTF metres, and back.
Eigen::Vector3d gltfFromLps(const Eigen::Vector3d& lpsMm);
Eigen::Vector3d lpsFromGltf(const Eigen::Vector3d& gltfMetres);

// The .glb bytes; throws BadInput naming `source` for a null or empty mesh, a colour outside 0..1 or a
// model too large for GLB's 32-bit lengths.
std::string formatGlb(const std::vector<GltfNode>& nodes, const std::string& source);
// Parses .glb bytes (see above); `source` names them in errors.
std::vector<GltfMesh> parseGlb(std::string_view bytes, const std::string& source);

// Through writeAtomically: no partial output, an existing `path` kept unless options.force (UsageError).
void writeGlb(const std::string& path, const std::vector<GltfNode>& nodes, const WriteOptions& options);
std::vector<GltfMesh> readGlb(const std::string& path);

// An anatomy as one node per tissue (named as the tissue, coloured by its kind, tissueKindColour) and the
// skin last, translucent (alpha `skinAlpha`, kSkinColour), named "skin". sRGB colours are converted to
// glTF's linear baseColorFactor so viewers show the same colours as our PNGs.
void writeAnatomyGlb(const std::string& path, const ReferenceAnatomy& anatomy, const WriteOptions& options,
                     double skinAlpha = 0.25);

// sRGB 0..255 -> linear 0..1 (IEC 61966-2-1), the space glTF colour factors are in.
std::array<double, 4> linearRgba(const DisplayColour& srgb, double alpha);

}  // namespace vesalius::io
