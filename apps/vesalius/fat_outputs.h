// What `vesalius fat` writes (docs/cli.md): thickness images and textures, meshes with the thickness as a
// point attribute, pictures, report metrics and the summary lines on stdout.
#pragma once

#include "thickness_input.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/mesh.h"
#include "vesalius/fat/erode_skin.h"
#include "vesalius/fat/thickness_texture.h"
#include "vesalius/io/report.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vesalius::cli {

// Fails before any work if an output would replace an input or an existing file without --force.
void checkOutputs(const std::vector<std::string>& outs, const std::vector<std::string>& ins, bool force);

// `fat forest`: the thickness image at `out` (float mm on skin voxels), the forest's statistics, and with
// `png` the thickness over three orthogonal slices.
void writeForestOutputs(const LoadedForest& l, const std::string& out, const std::string& png,
                        const WriteOptions& write, io::Report& report);

// `fat forest --surface --out-mesh`: the surface with the forest's thickness at its vertices.
void writeThicknessOnSurface(const std::string& surface, const std::string& outMesh, const fat::FatForest& forest,
                             double vertexRadiusMm, const WriteOptions& write, io::Report& report);

// `fat erode`: `mesh` moved to e.V with its attributes.
void writeErodedSkin(const std::string& out, TriMesh mesh, const Eigen::VectorXd& thickness, const fat::ErodedSkin& e,
                     const WriteOptions& write, io::Report& report);

// `fat texture`: the texture at `out`, its picture with `png`, and how well it reads back at the vertices.
void writeTextureOutputs(const std::string& out, const std::string& png, const TriMesh& mesh,
                         const std::string& skinPath, const Eigen::VectorXd& thickness,
                         const fat::ThicknessTexture& tex, const WriteOptions& write, io::Report& report);

// `fat edit`: the reference skin with the thickness (outMesh), its texture of size² texels (out) and
// picture (png), the body coloured by thickness (bodyPng); empty paths are skipped.
struct EditOutputs {
  std::string out, outMesh, png, bodyPng;
  int size = 1024;
};
void writeEditOutputs(const EditOutputs& o, TriMesh skin, const std::string& skinPath, const Eigen::VectorXd& thickness,
                      const WriteOptions& write, io::Report& report);

}  // namespace vesalius::cli
