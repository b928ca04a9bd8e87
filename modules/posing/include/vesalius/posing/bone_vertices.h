// Bone regions of a labelled tet mesh (Sujar et al. 2018, §3.2-3.3: "the tetrahedral mesh is tagged using the
// osseous model"; W_j = 1 inside the tets labelled j): the vertices of the tets of each bone's labels.
//
// Where two bones touch (a femoral head in its acetabulum at coarse voxels, a vertebra on the next), a
// vertex belongs to the tets of both but can follow only one; it goes to the bone listed later. Where a
// soft-tissue tet spans two bones (a joint space thinner than a tet), the vertices of the earlier bone
// in it are left free: with four rigid corners of two bones it would be crushed or inverted by the joint's
// turn, and nothing could repair it (untangle_tets.h moves only free vertices). Skeletons list children
// after their parents (core/skeleton.h), so the distal bone moves wholly rigidly and the proximal bone's
// contact surface blends between the two. A bone that would lose every vertex keeps them. Deviation from
// Sujar et al. 2018, whose bone voxels are apart: it does not say.
#pragma once

#include "vesalius/core/label_map.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace vesalius::posing {

// T: #T by 4 tets, tetLabel: #T labels, labelsOfBone: per bone, the labels of its tets. Returns #V
// (vertexCount) bone indices, -1 for a vertex of no bone's tet. Throws BadInput if tetLabel's size is not
// #T or a tet refers to a vertex outside 0..vertexCount-1.
Eigen::VectorXi boneVerticesOfLabels(const MatrixX4i& T, const Eigen::VectorXi& tetLabel,
                                     const std::vector<std::vector<Label>>& labelsOfBone, Eigen::Index vertexCount);

}  // namespace vesalius::posing
