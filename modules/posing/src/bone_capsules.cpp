#include "vesalius/posing/bone_capsules.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vesalius::posing {
namespace {

struct Capsule {
  int joint = -1;
  Eigen::Vector3d a, b;
  double radius = 0;
};

double distanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

std::vector<Capsule> capsules(const Skeleton& skeleton, const TriMesh& skin, const BoneCapsuleOptions& options) {
  const TriangleTree tree(skin.V, skin.F);
  const std::vector<Eigen::Isometry3d> rest = skeleton.restWorld();
  std::vector<Capsule> out;
  for (std::size_t j = 0; j < rest.size(); ++j) {
    if (skeleton.joints[j].tail.norm() == 0) continue;
    const Eigen::Vector3d head = rest[j].translation(), tail = rest[j] * skeleton.joints[j].tail;
    Capsule c{int(j), head + options.endTrim * (tail - head), tail - options.endTrim * (tail - head), 0};
    double clearance = std::numeric_limits<double>::infinity();
    for (int k = 0; k < options.samples; ++k) {
      const Eigen::Vector3d p = c.a + (c.b - c.a) * (k / double(options.samples - 1));
      clearance = std::min(clearance, std::sqrt(tree.closest(p).squaredDistance));
    }
    c.radius = options.radiusFraction * clearance;
    if (c.radius > 0) out.push_back(c);
  }
  return out;
}

}  // namespace

Eigen::VectorXi boneCapsuleVertices(const MatrixX3d& V, const Skeleton& skeleton, const TriMesh& skin,
                                    const BoneCapsuleOptions& options) {
  if (!(options.radiusFraction > 0 && options.radiusFraction < 1) || !(options.endTrim >= 0 && options.endTrim < 0.5) ||
      options.samples < 2)
    throw UsageError("bone capsules: radiusFraction must be in (0, 1), endTrim in [0, 0.5), samples >= 2");
  if (skin.F.rows() == 0) throw BadInput("", "bone capsules: the skin has no triangles");
  // A segment that leaves the body has zero clearance somewhere and so no capsule; the skin does not
  // tell inside from outside here, so a segment wholly outside the body is the caller's to avoid.
  const std::vector<Capsule> bones = capsules(skeleton, skin, options);
  Eigen::VectorXi boneOf = Eigen::VectorXi::Constant(V.rows(), -1);
  tbb::parallel_for(Eigen::Index(0), V.rows(), [&](Eigen::Index v) {
    double best = 1.0;
    for (const Capsule& c : bones) {
      const double relative = distanceToSegment(V.row(v).transpose(), c.a, c.b) / c.radius;
      if (relative <= best) {
        best = relative;
        boneOf[v] = c.joint;
      }
    }
  });
  return boneOf;
}

}  // namespace vesalius::posing
