// Fat thickness as users give it on the command line: `--thickness` and `--fat` specs, and the skin and
// fat of a label map with the forest built from them (`fat forest`, `fat erode`, `fat texture`).
#pragma once

#include "common.h"

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"
#include "vesalius/fat/fat_forest.h"
#include "vesalius/io/report.h"

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <string>

namespace vesalius::cli {

// spec: a number (mm at every vertex), a texture image (one slice, from `fat texture`) read at the mesh's
// uv, a mesh file with the point attribute fat_thickness on the same vertices, or a text file of one value
// per vertex. `kind` says which. Returns #V values; throws UsageError for a negative number, BadInput
// naming the file for anything unreadable or of the wrong length.
Eigen::VectorXd readThickness(const std::string& spec, const TriMesh& skin, const std::string& skinPath,
                              std::string& kind);

// Where the skin and fat masks come from, and the forest's options (shared by forest, erode, texture).
struct ForestSource {
  std::string labels, grid, table, skinLabel = "skin", fatLabel = "subcutaneous_fat", fatMask;
  double maxDistance = std::numeric_limits<double>::infinity();
  double gatherRadius = -1, vertexRadius = 0;
};

// --labels and --grid (label_map_input.h; --labels required or not) and the forest's options.
void addForestSourceOptions(CLI::App& cmd, ForestSource& o, bool required);

// The masks and the forest of a ForestSource.
struct LoadedForest {
  LabelMap map;
  fat::Mask skin, fat;
  std::unique_ptr<fat::FatForest> forest;
};

// Reads the label map (and fat mask), checks that skin and fat have voxels (BadInput naming the file),
// builds the forest; its inputs, parameters and time go into `report`.
LoadedForest loadForest(const ForestSource& o, io::Report& report, Progress& progress);

// Thickness at the skin's vertices from `spec` (readThickness) if given, else from the forest
// (fat::thicknessAtVertices with source.vertexRadius); where it came from goes into `report`.
Eigen::VectorXd vertexThickness(const std::string& spec, const TriMesh& skin, const std::string& skinPath,
                                const LoadedForest& l, const ForestSource& source, io::Report& report);

}  // namespace vesalius::cli
