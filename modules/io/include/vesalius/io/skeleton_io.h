// Read-only skeleton formats: MakeHuman rigs (.mhskel + .mhw skin weights) and OpenSim models (.osim).
// Neither is written by Vesalius: we take these rigs from their authors' tools and never change them, so
// a writer would have no user (a posed result goes out as BVH, motion_io.h).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"

#include <Eigen/Core>

#include <string>
#include <string_view>

namespace vesalius::io {

// ---- MakeHuman (.mhskel, .mhw; MakeHuman 1.1 format version 110) ----
//
// A .mhskel is JSON: "joints": {name: [vertex indices of base.obj]} — a joint sits at the centre (mean)
// of its vertices — and "bones": {name: {"head": joint, "tail": joint, "parent": bone or null, ...}}.
// `baseVertices` is base.obj's #V by 3 vertex matrix (19158 vertices for MakeHuman's base.obj), in its
// units: decimetres, +Y up, as MakeHuman's mesh.
//
// Gives one Joint per bone, parents before children (depth-first from the roots, children in file
// order): restLocal is a pure translation, head minus the parent's head (the root's head for a root), so
// rest frames are aligned with the mesh axes as in MakeHuman's BVH export; `tail` is tail minus head.
// Bone rolls and rotation planes are not used. Throws BadInput naming the file for unknown joints or
// parents, cycles, vertex indices outside baseVertices, or malformed JSON.
Skeleton parseMakeHumanSkeleton(std::string_view text, const std::string& source, const Eigen::MatrixX3d& baseVertices);
Skeleton readMakeHumanSkeleton(const std::string& mhskelPath, const Eigen::MatrixX3d& baseVertices);

// The .mhskel's skeleton placed in `body`, so that a body of another shape gets its own joints rather
// than base.obj's. `body` is of base.obj's topology when it has all of base.obj's vertices or its first
// ones (the "body" group, which base.obj lists first: a body exported without MakeHuman's helpers), with
// base.obj's first faces (the same vertices joined the same way), in base.obj's units. Joints on body
// vertices are then the body's; most joints sit at the centres of MakeHuman's "joint-*" cubes inside
// the body, and those cube vertices move with the body's change from the base: the mean-value
// interpolation of its vertices' displacements (core/mean_value_coordinates.h), exact for a body
// stretched or sheared as a whole. A body of any other topology gets base.obj's joints.
Skeleton readMakeHumanSkeletonOfBody(const std::string& mhskelPath, const TriMesh& base, const TriMesh& body);

// Whether `body` has base.obj's topology (see above).
bool isMakeHumanBody(const TriMesh& base, const TriMesh& body);

// A .mhw is JSON: "weights": {bone: [[vertex, weight], ...]}. Gives #V (= vertexCount) by
// #skeleton.joints weights. Each weighted vertex's row is normalised to sum 1, as MakeHuman does on
// loading (the shipped default_weights.mhw has raw sums from 0.32 to 1.67); vertices without weights keep
// an empty row. Throws BadInput for a bone not in `skeleton`, a vertex outside [0, vertexCount), a
// negative or non-finite weight.
SkinWeights parseMakeHumanWeights(std::string_view text, const std::string& source, const Skeleton& skeleton,
                                  int vertexCount);
SkinWeights readMakeHumanWeights(const std::string& mhwPath, const Skeleton& skeleton, int vertexCount);

// ---- OpenSim 4 models (.osim, OpenSimDocument Version >= 40000) ----
//
// Lengths in metres as in the file (OpenSim's unit); callers scale to millimetres.
// - bodies: one Joint per <Body> of the BodySet (ground is not a joint: a body or point fixed to ground
//   has parent/body -1). restLocal is the body's frame relative to its parent body in the default pose
//   with every coordinate at 0: X_parentOffset * X_joint(q = 0) * inverse(X_childOffset), offsets from
//   the joint's PhysicalOffsetFrames (translation, orientation as body-fixed X-Y-Z Euler angles in
//   radians). A CustomJoint's SpatialTransform is evaluated at q = 0: rotations about rotation1..3 applied
//   body-fixed in that order, then translations along translation1..3 in the parent frame; every other
//   joint type is the identity at q = 0. Supported TransformAxis functions: Constant, LinearFunction,
//   PolynomialFunction, PiecewiseLinearFunction, SimmSpline, NaturalCubicSpline, MultiplierFunction.
//   Parents come before children. `tail` is zero.
// - geometry: every <Mesh> of every body's attached_geometry, with mesh_file (relative to the model's
//   Geometry folder) and scale_factors; a mesh attached to a frame other than its body is BadInput.
// - muscles: every force whose element name ends in "Muscle" (Millard2012EquilibriumMuscle,
//   Thelen2003Muscle, ...), with the points of its GeometryPath in file order: PathPoint and
//   ConditionalPathPoint with their fixed location (a conditional point is kept whatever its range),
//   MovingPathPoint with x/y/z_location evaluated at coordinate value 0. Wrap objects are not read.
// Throws BadInput naming the file for malformed XML, an OpenSim 3 model, unknown bodies or frames, a
// body without a joint, or an unsupported function.
MusculoskeletalModel readOpenSimModel(const std::string& osimPath);

}  // namespace vesalius::io
