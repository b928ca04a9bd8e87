// A bone mesh bent inside its skin by a smooth displacement (bone_deformation_into_skin.h).
#include "vesalius/transfer/bone_deformation_into_skin.h"

#include "vesalius/core/error.h"
#include "vesalius/fit/smooth_displacement.h"

#include <cmath>
#include <vector>

namespace vesalius::transfer {

namespace {

long countOutside(const SkinDistances& d) { return long((d.distance.array() > 0).count()); }

// The shallow vertices' way out along `direction` (unit): per shallow vertex, the first of the points
// 1, 2, … reachMm mm along it that lies the margin inside, as a move; NaN where none does (the way leads
// out of the body, or past the reach).
MatrixX3d exitsAlong(const MatrixX3d& X, const std::vector<Eigen::Index>& shallow, const Eigen::Vector3d& direction,
                     const IntoSkinDeformationOptions& o, const SkinDistanceFunction& skin) {
  const int samples = int(std::floor(o.reachMm));
  MatrixX3d probes(Eigen::Index(shallow.size()) * samples, 3);
  for (std::size_t s = 0; s < shallow.size(); ++s)
    for (int k = 0; k < samples; ++k)
      probes.row(Eigen::Index(s) * samples + k) = X.row(shallow[s]) + double(k + 1) * direction.transpose();
  const Eigen::VectorXd d = skin(probes).distance;
  MatrixX3d exits = MatrixX3d::Constant(Eigen::Index(shallow.size()), 3, std::nan(""));
  for (std::size_t s = 0; s < shallow.size(); ++s)
    for (int k = 0; k < samples; ++k)
      if (d[Eigen::Index(s) * samples + k] <= -o.marginMm) {
        exits.row(Eigen::Index(s)) = double(k + 1) * direction.transpose();
        break;
      }
  return exits;
}

// Each vertex's wish and its weight: a shallow vertex (d > −margin) out along the preferred direction where
// that reaches the margin inside (exitsAlong), else onto its closest skin point and the margin beyond it,
// weight 1; a deep one to stay, weight keepWeight. Returns how many are shallow.
long wishes(const MatrixX3d& X, const SkinDistances& d, const IntoSkinDeformationOptions& o,
            const SkinDistanceFunction& skin, MatrixX3d& move, Eigen::VectorXd& weight) {
  move.setZero(X.rows(), 3);
  weight.setConstant(X.rows(), o.keepWeight);
  std::vector<Eigen::Index> shallow;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    const double residual = d.distance[i] + o.marginMm;
    if (residual <= 0) continue;
    move.row(i) = -residual * d.outward.row(i);
    weight[i] = 1.0;
    shallow.push_back(i);
  }
  if (shallow.empty() || o.preferredDirection.isZero()) return long(shallow.size());
  const MatrixX3d exits = exitsAlong(X, shallow, o.preferredDirection.normalized(), o, skin);
  for (std::size_t s = 0; s < shallow.size(); ++s)
    if (exits.row(Eigen::Index(s)).allFinite() &&
        exits.row(Eigen::Index(s)).norm() <= o.detourFactor * move.row(shallow[s]).norm())
      move.row(shallow[s]) = exits.row(Eigen::Index(s));
  return long(shallow.size());
}

}  // namespace

IntoSkinDeformation deformationIntoSkin(const TriMesh& mesh, const SkinDistanceFunction& skin,
                                        const IntoSkinDeformationOptions& options) {
  if (mesh.V.rows() == 0 || mesh.F.rows() == 0) throw UsageError("deformationIntoSkin: an empty mesh");
  if (!(options.marginMm >= 0 && options.iterations >= 0 && options.smoothness > 0 && options.keepWeight >= 0 &&
        options.reachMm >= 0 && options.detourFactor >= 0 && options.preferredDirection.allFinite()))
    throw UsageError("deformationIntoSkin: options out of range");
  IntoSkinDeformation out;
  out.displacement = MatrixX3d::Zero(mesh.V.rows(), 3);
  TriMesh bent = mesh;
  SkinDistances d = skin(bent.V);
  out.outsideBefore = countOutside(d);
  MatrixX3d move;
  Eigen::VectorXd weight;
  while (out.steps < options.iterations && wishes(bent.V, d, options, skin, move, weight) > 0) {
    out.displacement += fit::smoothDisplacement(bent, bent.V, move, weight, {options.smoothness});
    bent.V = mesh.V + out.displacement;
    d = skin(bent.V);
    ++out.steps;
  }
  out.outsideAfter = countOutside(d);
  return out;
}

}  // namespace vesalius::transfer
