// Reference anatomies on disk (core/anatomy.h): a folder holding reference.json and one OBJ per mesh.
//
//   {"format": "vesalius-reference-anatomy", "version": 1, "name": "torso (example_ct)",
//    "coordinate_system": "LPS", "units": "mm",
//    "skin": "skin.obj", "skin_cut_vertices": [12, 13, ...],
//    "sagittal_plane": {"point": [x, y, z], "normal": [x, y, z]},
//    "tissues": [{"name": "hip_left", "kind": "bone", "group": "pelvis", "symmetric": true,
//                 "file": "tissues/hip_left.obj"}, ...],
//    "points": [{"name": "...", "tissue": "femur_left", "position": [x, y, z]}, ...]}
//
// Mesh paths are relative to the folder. A transfer's output is written in the same form, so a
// transferred anatomy can be a reference in turn (docs/formats.md).
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/atomic_file.h"

#include <string>
#include <utility>
#include <vector>

namespace vesalius::io {

// The group of the full-body reference's skull and jaw, which `reference full-body` cuts out of OpenSim's
// torso body (Dicko et al. 2013, §8, gives each trunk bone a map of its own) and `rig --reference` moves with the torso.
inline constexpr const char* kSkullGroup = "skull";

// The file of a tissue in a reference folder, relative to it: "tissues/<name>.obj" with the name made safe
// (core/safe_file_name.h: a name from a file never becomes a path).
std::string tissueFile(const std::string& name);

// Throws BadInput naming the file (reference.json or a mesh) for anything missing or malformed.
ReferenceAnatomy readReferenceAnatomy(const std::string& folder);

// Writes the folder whole or not at all (core/atomic_file.h writeFolderAtomically: staged beside it,
// moved into place at the end; an existing folder is replaced only with options.force, else UsageError;
// its parent must exist). `extras`: more meshes to put in the folder beside the anatomy (file name, mesh),
// not listed in reference.json.
void writeReferenceAnatomy(const std::string& folder, const ReferenceAnatomy& anatomy, const WriteOptions& options,
                           const std::vector<std::pair<std::string, TriMesh>>& extras = {});

}  // namespace vesalius::io
