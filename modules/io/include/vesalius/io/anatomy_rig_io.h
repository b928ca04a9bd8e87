// The folder of an anatomy rig (core/anatomy_rig.h), as `vesalius rig` and `vesalius patient` write it and
// `vesalius pose` reads it (docs/cli.md):
//   DIR/rig.vtu        rest tet mesh of the body (mm, LPS); point data "bone" (column of the vertex's bone
//                      in "weights", -1 for tissue), "weights" (#V by #B, Sujar et al. 2018, §3.3), with
//                      `rig --cor-centres` "cor_centre" (#V by 3, centres of rotation, §3.5);
//                      cell data "label" (1: body)
//   DIR/bones.txt      the skeleton joint of each column of "weights", one name a line
//   DIR/skeleton.bvh   the skeleton at rest (mm, LPS: written with no axis change), one frame of zeros;
//                      BVH has no rest rotations, so its joints keep their positions with unrotated frames
//   DIR/frames.txt     only for a skeleton with rotated rest frames (`rig --labels`, Sujar et al. 2018, §3.1): per
//                      joint "name" and its rest world rotation, 9 numbers row by row
//   DIR/meshes/*       the meshes at rest (mm, LPS): skin.<ext> (the body surface the rig was built from)
//                      and the tissue meshes under their own file names; each is posed under its name
//   DIR/bone_meshes.txt  only when the rig has bone meshes (AnatomyRig::meshJoint): per bone mesh "file of
//                      meshes/", a tab and the joint it moves with rigidly
// The other meshes are embedded in the tets (core/tet_embedding.h) when a pose run starts: that takes
// milliseconds, while the weights and centres stored here take the seconds.
#pragma once

#include "vesalius/core/anatomy_rig.h"
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"

#include <Eigen/Geometry>

#include <string>
#include <utility>
#include <vector>

namespace vesalius::io {

// Writes rig.vtu, bones.txt, skeleton.bvh (and frames.txt, bone_meshes.txt) and meshes/<name> for each
// (name, mesh), in rig.meshJoint's order, as the folder `dir`, whole or not at all (writeFolderAtomically:
// an existing folder is replaced only with options.force, its parent must exist); names are made safe file
// names, their extensions pick the format; two meshes whose names give one file are refused (BadInput
// naming `dir`).
void writeAnatomyRig(const std::string& dir, const AnatomyRig& rig,
                     const std::vector<std::pair<std::string, TriMesh>>& meshes, const WriteOptions& options);

// The rig of `dir`, its meshes as their paths (sorted). Throws BadInput naming the file that is missing or
// does not match the others.
AnatomyRig readAnatomyRig(const std::string& dir);

// The posed skeleton as BVH: `rest`'s hierarchy with one frame whose channels give `posedWorld`. BVH
// offsets carry no rotation, so a rotated rest frame is written unrotated at its joint, posed by the same
// rest-to-posed map posedWorld_j · restWorld_j⁻¹ (the skinning transform, which is thus kept).
Motion posedSkeletonMotion(const Skeleton& rest, const std::vector<Eigen::Isometry3d>& posedWorld);

}  // namespace vesalius::io
