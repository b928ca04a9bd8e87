// What the per-frame post-steps of skinning (volume_restoration.h, untangle_tets.h) check of the rest rig
// they are built on.
#pragma once

#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::posing {

// The rest volume of each of T's tets. Throws BadInput, its message starting with `step`, if boneOfVertex
// is not #V long, a tet refers to a vertex outside restV, or a tet is flat or inverted at rest.
inline Eigen::VectorXd checkedRestVolumes(const std::string& step, const MatrixX3d& restV, const MatrixX4i& T,
                                          const Eigen::VectorXi& boneOfVertex) {
  if (boneOfVertex.size() != restV.rows())
    throw BadInput("", step + ": " + std::to_string(boneOfVertex.size()) + " bone indices for " +
                           std::to_string(restV.rows()) + " vertices");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= restV.rows()))
    throw BadInput("", step + ": a tet refers to a vertex outside the mesh");
  Eigen::VectorXd volume = tetVolumes(restV, T);
  for (Eigen::Index t = 0; t < T.rows(); ++t)
    if (!(volume[t] > 0)) throw BadInput("", step + ": tet " + std::to_string(t) + " is flat or inverted at rest");
  return volume;
}

}  // namespace vesalius::posing
