// Fat thickness as users give it on the command line (`fat erode --thickness`, `transfer --fat`).
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::cli {

// spec: a number (mm at every vertex), a texture image (one slice, from `fat texture`) read at the mesh's
// uv, a mesh file with the point attribute fat_thickness on the same vertices, or a text file of one value
// per vertex. `kind` says which. Returns #V values; throws UsageError for a negative number, BadInput
// naming the file for anything unreadable or of the wrong length.
Eigen::VectorXd readThickness(const std::string& spec, const TriMesh& skin, const std::string& skinPath,
                              std::string& kind);

}  // namespace vesalius::cli
