// MakeHuman's shape targets (.target): per line "vertex dx dy dz", an offset of one base.obj vertex in
// base.obj's units (decimetres, +Y up), '#' comments. A body of another age, sex, weight or muscle is
// the base mesh plus the targets, each at its weight (MakeHuman's macro sliders blend several; adding
// them at weight 1 gives the sliders' extremes).
#pragma once

#include "vesalius/core/mesh.h"

#include <string>
#include <string_view>

namespace vesalius::io {

struct MakeHumanTarget {
  Eigen::VectorXi vertex;  // #K base.obj vertex indices
  MatrixX3d offset;        // #K by 3, base.obj's units
};

// Throws BadInput naming `source` for a line that is not an index and three finite numbers, or a
// negative index.
MakeHumanTarget parseMakeHumanTarget(std::string_view text, const std::string& source);
MakeHumanTarget readMakeHumanTarget(const std::string& path);

// `body` (base.obj's vertices or its first ones, makehuman skeleton_io.h) with `weight` times the target's
// offsets added; offsets of vertices the body does not have (MakeHuman's helpers) are skipped.
TriMesh applyMakeHumanTarget(TriMesh body, const MakeHumanTarget& target, double weight = 1.0);

}  // namespace vesalius::io
