// Target bodies for anatomy transfer made from the test CT (testdata/ct-abdomen-pelvis): its body mask,
// optionally dilated (more fat) and its spacing scaled (a wider or flatter person), surfaced anew; and the
// fat layer of such a body measured per reference skin vertex. Shared by the transfer integration tests
// (tests/apps/cli_transfer_test.cpp) and the whole-transfer benchmark (tests/bench/bench_transfer_whole.cpp).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/segmentation/label_ops.h"

#include <cmath>
#include <fstream>
#include <string>

namespace vesalius::test {

// The body of the CT at `ctPath` surfaced after `dilateMm` of extra tissue, on a grid whose spacing is
// scaled by `stretch`, centred where the original body was; written to DIR/target.obj, whose path is
// returned. 16,000 faces: a mesh unlike a torso reference skin's 20,000.
inline std::string ctBodySurface(const std::string& ctPath, const std::string& dir, double dilateMm,
                                 const Eigen::Vector3d& stretch) {
  const Image ct = io::readScan(ctPath);
  segmentation::Mask body = segmentation::segmentCtBody(ct, {});
  if (dilateMm > 0) body = segmentation::dilateMm(body, dilateMm);
  const Eigen::Vector3d centre = body.geometry.indexToWorld(0.5 * (body.geometry.size.cast<double>() - Eigen::Vector3d::Ones()));
  body.geometry.spacing = body.geometry.spacing.cwiseProduct(stretch);
  body.geometry.origin += centre - body.geometry.indexToWorld(0.5 * (body.geometry.size.cast<double>() - Eigen::Vector3d::Ones()));
  meshing::SurfaceOptions surface;
  surface.targetFaces = 16000;
  const std::string path = dir + "/target.obj";
  io::writeTriMesh(path, meshing::labelSurface(segmentation::labelMapOf(body, {1, "body"}), 1, surface));
  return path;
}

// The fat layer a forest would measure on a fatter body: the distance (mm) from each reference skin vertex
// out to the body surface at `targetPath`, one value a line in `outPath` (as `transfer --fat FILE` takes it).
inline void writeFatLayer(const TriMesh& referenceSkin, const std::string& targetPath, const std::string& outPath) {
  const TriMesh target = io::readTriMesh(targetPath);
  const TriangleTree tree(target.V, target.F);
  std::ofstream fat(outPath);
  for (const ClosestPoint& c : tree.closest(referenceSkin.V)) fat << std::sqrt(c.squaredDistance) << "\n";
}

}  // namespace vesalius::test
