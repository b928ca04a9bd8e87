// The labelled region of a bone where it faces another (Sujar et al. 2018, §3.1: joint centres and axes are fitted
// to "a set of annotated vertices"): the points of one bone within a distance of the other. The femoral
// head is the femur's part near the hip bone, the condyles its part near the tibia, the talar trochlea the
// talus's part near the tibia (skeleton_from_bones.h from voxels, skeleton_from_bone_meshes.h from meshes).
//
// Against points (voxel centres) the distance is to the nearest point; against a mesh it is to its
// surface, not its vertices, since bone meshes can be coarse (the OpenSim ones space vertices ~1 cm apart).
#pragma once

#include "vesalius/core/mesh.h"

namespace vesalius::posing {

// A: #A by 3 points; B: #B by 3 points. Returns the rows of A within `distance` of some row of B, in order.
MatrixX3d pointsNear(const MatrixX3d& A, const MatrixX3d& B, double distance);

// A: #A by 3 points; B: a triangle mesh. Returns the rows of A within `distance` of B's surface, in order
// (none if B has no triangles).
MatrixX3d pointsNear(const MatrixX3d& A, const TriMesh& B, double distance);

// A: #A by 3 points; B: a triangle mesh. Returns the rows of A within `reach` of B's surface beyond the
// nearest of them, in order: the part of A facing B whether the two touch or stand apart (two bones of a
// placed model need not meet; rig --reference's humeri stand off their glenoids). None if A or B is empty.
MatrixX3d pointsNearest(const MatrixX3d& A, const TriMesh& B, double reach);

}  // namespace vesalius::posing
