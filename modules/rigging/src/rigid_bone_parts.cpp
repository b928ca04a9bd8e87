#include "vesalius/rigging/rigid_bone_parts.h"

#include "vesalius/core/error.h"
#include "vesalius/meshing/winding_mask.h"
#include "vesalius/posing/skeleton_pose.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace vesalius::rigging {
namespace {

// A voxel inside the posed bones of two joints (a femoral head in its socket, whose winding number the
// cup lifts to a half): neither joint's map is right for all of it, so the tets carry it.
constexpr Label kContested = std::numeric_limits<Label>::max();

// The continuous index box of V on grid g.
struct IndexRange {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
};
IndexRange indexRange(const MatrixX3d& V, const GridGeometry& g) {
  IndexRange r;
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Eigen::Vector3d index = g.worldToIndex(V.row(v).transpose());
    r.lo = r.lo.cwiseMin(index);
    r.hi = r.hi.cwiseMax(index);
  }
  return r;
}

// Whether the box reaches a voxel of g (beyond half a voxel of its edge centres, nothing is sampled).
bool meets(const IndexRange& r, const GridGeometry& g) {
  return (r.hi.array() >= -0.5).all() && (r.lo.array() <= g.size.cast<double>().array() - 0.5).all();
}

}  // namespace

posing::RigidParts rigidBoneParts(const AnatomyRig& rig, const std::vector<TriMesh>& restMeshes,
                                  const std::vector<MatrixX3d>& posedMeshes,
                                  const std::vector<Eigen::Isometry3d>& world, const GridGeometry& scan,
                                  const GridGeometry& out) {
  if (restMeshes.size() != rig.meshes.size() || posedMeshes.size() != rig.meshes.size())
    throw BadInput("", "rigid bone parts: " + std::to_string(restMeshes.size()) + " rest and " +
                           std::to_string(posedMeshes.size()) + " posed meshes for a rig of " +
                           std::to_string(rig.meshes.size()));
  posing::RigidParts rigid;
  if (rig.meshJoint.empty()) return rigid;
  rigid.parts = Grid<Label>(out, 0);
  for (const Eigen::Isometry3d& map : posing::restToPosed(rig.skeleton, world)) rigid.restFromPosed.push_back(map.inverse());
  for (std::size_t m = 0; m < rig.meshes.size(); ++m) {
    const int joint = rig.jointOfMesh(m);
    if (joint < 0 || restMeshes[m].F.rows() == 0 || !meets(indexRange(restMeshes[m].V, scan), scan)) continue;
    const IndexRange posed = indexRange(posedMeshes[m], out);
    if (!meets(posed, out)) continue;
    // The mesh is voxelized on the part of `out` its posed box covers.
    const Eigen::Vector3i lo = posed.lo.array().ceil().cast<int>().max(0);
    const Eigen::Vector3i hi = posed.hi.array().floor().cast<int>().min(out.size.array() - 1);
    if ((lo.array() > hi.array()).any()) continue;
    GridGeometry box = out;
    box.origin = out.indexToWorld(lo.cast<double>());
    box.size = hi - lo + Eigen::Vector3i::Ones();
    const Grid<std::uint8_t> inside = meshing::windingNumberMask(TriMesh{posedMeshes[m], restMeshes[m].F, {}, {}, {}, {}}, box);
    for (int k = 0; k < box.size.z(); ++k)
      for (int j = 0; j < box.size.y(); ++j)
        for (int i = 0; i < box.size.x(); ++i) {
          Label& part = rigid.parts.at(lo.x() + i, lo.y() + j, lo.z() + k);
          if (inside.at(i, j, k)) part = part == 0 || part == Label(joint + 1) ? Label(joint + 1) : kContested;
        }
  }
  for (Label& part : rigid.parts.values)
    if (part == kContested) part = 0;
  return rigid;
}

}  // namespace vesalius::rigging
