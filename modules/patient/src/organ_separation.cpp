// Fitted organs separated where they touch (organ_separation.h, Wang et al. 2021, §4.1.4).
#include "vesalius/patient/organ_separation.h"

#include "vesalius/core/error.h"
#include "vesalius/core/tet_locator.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fit/embedding.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace vesalius::patient {

namespace {

struct Penetration {
  long vertices = 0;
  double maxDepth = 0;  // mm
};

// Boundary vertices of `a` inside a tet of `b`, and how far the deepest lies below b's boundary.
Penetration penetrationOf(const TetMesh& a, const TetMesh& b) {
  const MatrixX3i F = tetBoundary(a.T);
  std::vector<int> boundary(F.data(), F.data() + F.size());
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  const TetLocator locator(b.V, b.T);
  const TriangleTree surface(b.V, tetBoundary(b.T));
  std::vector<double> depth(boundary.size(), -1.0);
  tbb::parallel_for(std::size_t(0), boundary.size(), [&](std::size_t i) {
    const Eigen::Vector3d p = a.V.row(boundary[i]).transpose();
    if (locator.locate(p)) depth[i] = std::sqrt(surface.closest(p).squaredDistance);
  });
  Penetration out;
  for (const double d : depth)
    if (d >= 0) ++out.vertices, out.maxDepth = std::max(out.maxDepth, d);
  return out;
}

Penetration penetrationBetween(const TetMesh& a, const TetMesh& b) {
  const Penetration ab = penetrationOf(a, b), ba = penetrationOf(b, a);
  return {ab.vertices + ba.vertices, std::max(ab.maxDepth, ba.maxDepth)};
}

}  // namespace

std::vector<OrganPairSeparation> separateOrgans(const std::vector<OrganFit*>& organs,
                                                const OrganSeparationOptions& options) {
  std::vector<TetMesh> meshes;
  for (std::size_t i = 0; i < organs.size(); ++i) {
    if (!organs[i]) throw UsageError("separateOrgans: organ " + std::to_string(i) + " is null");
    if (organs[i]->tets.T.rows() == 0 || organs[i]->tets.V.rows() == 0)
      throw UsageError("separateOrgans: organ " + std::to_string(i) + " has no fitted tets");
    meshes.push_back(organs[i]->tets);
  }

  std::vector<OrganPairSeparation> pairs;
  for (std::size_t k = 1; k < meshes.size(); ++k)
    for (std::size_t j = 0; j < k; ++j) {
      const Penetration before = penetrationBetween(meshes[k], meshes[j]);
      OrganPairSeparation p;
      p.first = j;
      p.second = k;
      p.penetratingBefore = before.vertices;
      p.maxDepthBefore = before.maxDepth;
      pairs.push_back(p);
    }
  if (meshes.size() < 2) return pairs;

  // On copies: a failure in a later pair leaves every fit as it was.
  const std::vector<fit::InterpenetrationReport> solved = fit::removeInterpenetrations(meshes, options.solver);
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    OrganPairSeparation& p = pairs[n];
    const Penetration after = penetrationBetween(meshes[p.second], meshes[p.first]);
    p.penetratingAfter = after.vertices;
    p.maxDepthAfter = after.maxDepth;
    p.rounds = solved[n].rounds;
    p.maxDisplacement = solved[n].maxDisplacement;
  }

  for (std::size_t i = 0; i < organs.size(); ++i) {
    OrganFit& fit = *organs[i];
    if (meshes[i].V == fit.tets.V) continue;  // not in contact: nothing moved
    // The carried template moves with the tets around it: embedded in them as fitted, carried to where the
    // separation put them (vertices of tets outside the contact regions did not move, nor do theirs).
    fit.carriedTemplate = fit::embedSurface(fit.carriedTemplate, fit.tets.V, fit.tets.T, meshes[i].V);
    fit.tets.V = meshes[i].V;
    fit.surface = tetBoundarySurface(fit.tets.V, fit.tets.T);
  }
  return pairs;
}

transfer::TissuesBentApart bendOrgansOffLabels(ReferenceAnatomy& anatomy, const std::vector<std::string>& names,
                                               const std::vector<OrganFit*>& fits, const GridGeometry& scan,
                                               const transfer::InsideSkinWarpOptions& options) {
  if (names.size() != fits.size()) throw UsageError("bendOrgansOffLabels: one fit per name is needed");
  std::vector<ReferenceTissue*> fitted;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto t = std::find_if(anatomy.tissues.begin(), anatomy.tissues.end(),
                                [&](const ReferenceTissue& r) { return r.name == names[i]; });
    if (t == anatomy.tissues.end() || !fits[i])
      throw UsageError("bendOrgansOffLabels: no tissue or no fit for organ '" + names[i] + "'");
    fitted.push_back(&*t);
  }
  std::vector<transfer::BendRole> roles;
  for (const ReferenceTissue& t : anatomy.tissues)
    roles.push_back(std::find(names.begin(), names.end(), t.name) != names.end() ? transfer::BendRole::Bent
                                                                                : transfer::BendRole::Fixed);
  const transfer::SkinDistanceFunction noSkin = [](const MatrixX3d& P) {
    return transfer::SkinDistances{Eigen::VectorXd::Constant(P.rows(), -std::numeric_limits<double>::infinity()),
                                   MatrixX3d::Zero(P.rows(), 3)};
  };
  transfer::TissuesBentApart bent =
      transfer::bendTissuesApart(anatomy, roles, noSkin, options, {transfer::Straddle::Dent, &scan});
  if (bent.bend.centres.empty()) return bent;
  for (std::size_t i = 0; i < fits.size(); ++i) {
    OrganFit& fit = *fits[i];
    fit.tets.V = bent.bend.apply(fit.tets.V);
    fit.surface = tetBoundarySurface(fit.tets.V, fit.tets.T);
    fit.carriedTemplate.V = bent.bend.apply(fit.carriedTemplate.V);
    fitted[i]->mesh = fit.surface;
  }
  return bent;
}

}  // namespace vesalius::patient
