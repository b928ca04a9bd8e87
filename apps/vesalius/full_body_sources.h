// The files of the full-body reference (patient/full_body_reference.h) read into its sources, in mm LPS:
// a MakeHuman skin (decimetres, +Y up; its uv from base.obj if it has none), MakeHuman's default rig and
// an OpenSim model with its Geometry folder beside it. Shared by `reference full-body` and `patient`.
#pragma once

#include "vesalius/patient/full_body_reference.h"

#include <string>

namespace vesalius::cli {

// baseMesh: MakeHuman's base.obj for the rig and the skin's uv; empty for the one beside the rig. Throws
// BadInput naming the file that cannot be read.
patient::FullBodySources readFullBodySources(const std::string& skin, const std::string& skeleton,
                                             const std::string& baseMesh, const std::string& model);

}  // namespace vesalius::cli
