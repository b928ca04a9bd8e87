// The posing rig of an anatomy (Sujar et al. 2018, §3.1-3.5 preprocessing): the rest tet mesh of the inside of the
// body with its bone regions, the bone weights and centres of rotation as vertex attributes, the skeleton
// whose joints the weights follow, and the names of the meshes the rig carries. `rigging` builds it,
// `posing` poses it, io/anatomy_rig_io.h keeps it in a folder.
#pragma once

#include "vesalius/core/error.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vesalius {

struct AnatomyRig {
  // Rest tets, mm LPS. Vertex attributes: "bone" (#V: the column of the vertex's bone in "weights", -1 for
  // tissue), "weights" (#V by #B, Sujar et al. 2018, §3.3), and "cor_centre" (#V by 3, centres of rotation, §3.5)
  // when they were computed.
  TetMesh tets;
  Skeleton skeleton;                // rest, mm LPS
  std::vector<int> boneJoint;       // #B: the joint of each weight column
  // The meshes the rig carries, as file names (their stems name them: "skin" is the body surface); the
  // paths of the files when read from a rig folder.
  std::vector<std::string> meshes;
  // Empty, or one per mesh: the joint a bone mesh moves with rigidly (by the joint's rest-to-posed map, as
  // the bone's own tet vertices do), -1 for a mesh the tets carry. Bones carried by the tets would bend
  // where tissue next to them is squeezed.
  std::vector<int> meshJoint;

  // The joint mesh m moves with rigidly, -1 if the tets carry it.
  int jointOfMesh(std::size_t m) const { return m < meshJoint.size() ? meshJoint[m] : -1; }

  const Eigen::MatrixXd& weights() const { return tets.vertexAttributes.real.at("weights"); }
  const Eigen::VectorXi& boneOfVertex() const { return tets.vertexAttributes.integer.at("bone"); }
  bool hasCentres() const {
    const auto found = tets.vertexAttributes.real.find("cor_centre");
    return found != tets.vertexAttributes.real.end() && found->second.cols() == 3;
  }
  // Throws BadInput naming rig.vtu if the rig has no centres of rotation.
  MatrixX3d centres() const {
    if (!hasCentres())
      throw BadInput("rig.vtu", "has no centres of rotation for CoR skinning (it was made with --no-cor-centres; "
                                "run `vesalius rig` without it)");
    return tets.vertexAttributes.real.at("cor_centre");
  }
};

}  // namespace vesalius
