// Bone attachments (attachments.h, Wang et al. 2021, §4.1.2).
#include "vesalius/fit/attachments.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <cmath>
#include <vector>

namespace vesalius::fit {

BoneAttachments boneAttachments(const MatrixX3d& placedV, const MatrixX4i& T, const MatrixX3d& restV,
                                const TriMesh& bone, double radius) {
  if (!(radius > 0)) throw UsageError("attachments: the radius must be positive");
  if (placedV.rows() != restV.rows())
    throw UsageError("attachments: placed and rest positions differ in number of vertices");
  if (bone.F.rows() == 0) throw BadInput("", "attachments: the bone surface has no triangles");
  const MatrixX3i F = tetBoundary(T);
  if (F.rows() == 0) throw BadInput("", "attachments: the template has no boundary triangles");
  const std::vector<ClosestPoint> hits = TriangleTree(placedV, F).closest(bone.V);
  std::vector<Eigen::Index> attached;
  for (Eigen::Index v = 0; v < bone.V.rows(); ++v)
    if (hits[std::size_t(v)].squaredDistance <= radius * radius) attached.push_back(v);

  BoneAttachments a;
  const Eigen::Index count = Eigen::Index(attached.size());
  a.material.resize(count, 3);
  a.targets.resize(count, 3);
  a.boneVertices.resize(count);
  a.distances.resize(count);
  for (Eigen::Index k = 0; k < count; ++k) {
    const Eigen::Index v = attached[std::size_t(k)];
    const ClosestPoint& hit = hits[std::size_t(v)];
    a.material.row(k).setZero();
    for (int corner = 0; corner < 3; ++corner)
      a.material.row(k) += hit.barycentric[corner] * restV.row(F(hit.face, corner));
    a.targets.row(k) = bone.V.row(v);
    a.boneVertices[k] = int(v);
    a.distances[k] = std::sqrt(hit.squaredDistance);
  }
  return a;
}

}  // namespace vesalius::fit
