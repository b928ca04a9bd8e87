// Attachments of a template organ to a bone (Wang et al. 2021, §4.1.2 and §3.1): the bone vertices where the organ
// inserts become soft constraints, each tying a material point of the organ to the bone vertex.
//
// Every vertex of `bone` within a radius R of the placed template's surface is attached, so `bone` should
// be the insertion itself (Wang et al.'s are marked by hand; from a label map, the bone's interface with the
// muscle label, meshing/shared_label_surfaces.h interfaceOfLabels). Given a whole bone, R must cover the
// placement's error, and the band within R is attached also where other tissue lies between bone and
// muscle: on the test CT's gluteus medius (hip within 5 mm: 1,226 vertices; the hip's interface with the
// muscle label has 324) the fit stopped at 0.76 mm mean ICP error, against 0.23 mm attached to the
// insertion (docs/methods/plastic-fit.md). Each attached vertex's material point is its closest point on the placed
// template's surface, expressed by the barycentric weights of that boundary triangle and mapped back to
// the triangle's rest (template-space) corners; its target is the bone vertex itself. (Wang et al. 2021 marks the
// insertion by hand and takes the closest tet; with the template placed on the scan, the closest surface
// point is that tet's boundary point.)
#pragma once

#include "vesalius/core/mesh.h"

#include <Eigen/Core>

namespace vesalius::fit {

struct BoneAttachments {
  MatrixX3d material;            // #A by 3 material points on the template's rest surface (template space)
  MatrixX3d targets;             // #A by 3 the bone vertices they are tied to (world, mm)
  Eigen::VectorXi boneVertices;  // #A rows of bone.V that were attached
  Eigen::VectorXd distances;     // #A distances (mm) from each bone vertex to the placed template surface
};

// placedV: #V by 3 template positions placed on the scan (world mm), T: #T by 4 tets, restV: #V by 3 the
// template's rest positions (same numbering); bone: the bone surface in world mm; radius in mm. Bone
// vertices at distance <= radius are attached, in bone vertex order. Throws BadInput if the tet mesh has
// no boundary or the bone no triangles, UsageError if radius is not positive or the positions differ in size.
BoneAttachments boneAttachments(const MatrixX3d& placedV, const MatrixX4i& T, const MatrixX3d& restV,
                                const TriMesh& bone, double radius);

}  // namespace vesalius::fit
