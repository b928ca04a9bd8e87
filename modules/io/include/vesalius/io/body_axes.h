// Bodies and motions from their authors' axes and units into Vesalius's space (millimetres, LPS).
//
// BVH motions and MakeHuman bodies and rigs use +Y up, the body facing +Z, its left at +X; MakeHuman's are
// in decimetres. OpenSim models use +Y up, the body facing +X, its right at +Z, in metres. The readers
// keep the files' own axes and units (motion_io.h, skeleton_io.h, mesh_io.h); the apps move what they
// read into LPS millimetres with these, at their edge.
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"

#include <Eigen/Core>

namespace vesalius::io {

// Rotation from +Y-up, +Z-forward, +X-left axes (BVH, MakeHuman) to LPS: L = X, P = −Z, S = Y.
Eigen::Matrix3d yUpToLps();

// Rotation from OpenSim's axes (X anterior, Y superior, Z to the body's right; models in metres, so scale
// 1000) to LPS: L = −Z, P = −X, S = Y.
Eigen::Matrix3d openSimToLps();

// Points in new axes: scale · axes · p per row of P (#P by 3).
MatrixX3d transformPoints(const MatrixX3d& P, const Eigen::Matrix3d& axes, double scale);

// The skeleton seen in new axes: every joint's world rest frame R, t becomes axes·R·axesᵀ, scale·axes·t
// (lengths scale, joint frames rotate with the body). `axes` must be a rotation, scale positive; throws
// UsageError otherwise.
Skeleton transformSkeleton(const Skeleton& skeleton, const Eigen::Matrix3d& axes, double scale);

}  // namespace vesalius::io
