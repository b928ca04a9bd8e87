// Anatomy transfer (anatomy_transfer.h).
#include "vesalius/transfer/anatomy_transfer.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/transfer/anatomy_checks.h"

#include <chrono>
#include <limits>
#include <map>
#include <unordered_map>

namespace vesalius::transfer {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

MatrixX3d stackRows(const std::vector<const MatrixX3d*>& parts) {
  Eigen::Index rows = 0;
  for (const MatrixX3d* part : parts) rows += part->rows();
  MatrixX3d stacked(rows, 3);
  rows = 0;
  for (const MatrixX3d* part : parts) stacked.middleRows(rows, part->rows()) = *part, rows += part->rows();
  return stacked;
}

// Bone tissues gathered into their groups, in the order the groups first appear; a free group of long
// bones only is marked so.
std::vector<BoneGroupMap> boneGroups(const ReferenceAnatomy& reference) {
  std::vector<BoneGroupMap> groups;
  std::map<std::string, int> index;
  for (int t = 0; t < int(reference.tissues.size()); ++t) {
    const ReferenceTissue& tissue = reference.tissues[t];
    if (tissue.kind != TissueKind::Bone) continue;
    const std::string name = tissue.group.empty() ? tissue.name : tissue.group;
    const auto [it, inserted] = index.emplace(name, int(groups.size()));
    if (inserted) {
      groups.emplace_back();
      groups.back().group = name;
      groups.back().symmetric = tissue.symmetric;
      groups.back().longBones = !tissue.symmetric;
    }
    groups[it->second].tissues.push_back(t);
    groups[it->second].longBones = groups[it->second].longBones && isLongBone(tissue.mesh.V);
  }
  return groups;
}

MatrixX3d groupVertices(const BoneGroupMap& group, const std::vector<MatrixX3d>& perTissue) {
  std::vector<const MatrixX3d*> parts;
  for (const int t : group.tissues) parts.push_back(&perTissue[t]);
  return stackRows(parts);
}

// Whether the cell nearest p and its six neighbours are all inside the body: bone vertices that are not
// (a bone that touches or pokes through the skin, as a segmentation's labels can where the field of view
// cuts both) would fix cells beside the skin's own and fold the field between the two.
bool deepInside(const Grid<std::uint8_t>& inside, const Eigen::Vector3d& p) {
  const GridGeometry& g = inside.geometry;
  const Eigen::Vector3d index = g.worldToIndex(p).array().round();
  const int i = int(index.x()), j = int(index.y()), k = int(index.z());
  for (const auto& d : {Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(1, 0, 0), Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, 1, 0),
                        Eigen::Vector3i(0, -1, 0), Eigen::Vector3i(0, 0, 1), Eigen::Vector3i(0, 0, -1)})
    if (!g.contains(i + d.x(), j + d.y(), k + d.z()) || !inside.at(i + d.x(), j + d.y(), k + d.z())) return false;
  return true;
}

// The rows of `rest` (and the same rows of `displacement`) that lie deep inside the body.
void appendDeepRows(const Grid<std::uint8_t>& inside, const MatrixX3d& rest, const MatrixX3d& displacement,
                    std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Vector3d>& values,
                    const std::vector<bool>& skip = {}) {
  for (Eigen::Index r = 0; r < rest.rows(); ++r)
    if (deepInside(inside, rest.row(r).transpose()) && (skip.empty() || !skip[std::size_t(r)]))
      points.push_back(rest.row(r).transpose()), values.push_back(displacement.row(r).transpose());
}

// Per bone tissue, its rows (rest positions) within `reach` cells of another group's bone: at a joint two
// groups' maps disagree (the muscular body's L5 comes down onto its sacrum, docs/methods/anatomy-transfer.md),
// and their fixed cells a couple of cells apart fold the free cells between them. Those rows fix nothing
// in the final field, which then passes from one map to the other harmonically; the bones still move by
// their own maps.
std::vector<std::vector<bool>> rowsAtJoints(const std::vector<BoneGroupMap>& groups, const std::vector<MatrixX3d>& rest,
                                            const GridGeometry& g, int reach) {
  const auto cellOf = [&g](const MatrixX3d& V, Eigen::Index r) -> Eigen::Vector3i {
    return g.worldToIndex(V.row(r).transpose()).array().round().cast<int>();
  };
  std::unordered_map<std::int64_t, int> owner;  // cell → the group whose bone is in it, −1 for several
  for (int gi = 0; gi < int(groups.size()); ++gi)
    for (const int t : groups[gi].tissues)
      for (Eigen::Index r = 0; r < rest[t].rows(); ++r) {
        const Eigen::Vector3i c = cellOf(rest[t], r);
        if (!g.contains(c.x(), c.y(), c.z())) continue;
        const auto [it, inserted] = owner.emplace(g.linearIndex(c.x(), c.y(), c.z()), gi);
        if (!inserted && it->second != gi) it->second = -1;
      }
  std::vector<std::vector<bool>> atJoint(rest.size());
  for (int gi = 0; gi < int(groups.size()); ++gi)
    for (const int t : groups[gi].tissues) {
      atJoint[t].assign(std::size_t(rest[t].rows()), false);
      for (Eigen::Index r = 0; r < rest[t].rows(); ++r) {
        const Eigen::Vector3i c = cellOf(rest[t], r);
        for (int dk = -reach; dk <= reach; ++dk)
          for (int dj = -reach; dj <= reach; ++dj)
            for (int di = -reach; di <= reach; ++di) {
              if (!g.contains(c.x() + di, c.y() + dj, c.z() + dk)) continue;
              const auto it = owner.find(g.linearIndex(c.x() + di, c.y() + dj, c.z() + dk));
              if (it != owner.end() && it->second != gi) atJoint[t][std::size_t(r)] = true;
            }
      }
    }
  return atJoint;
}

MatrixX3d toMatrix(const std::vector<Eigen::Vector3d>& rows) {
  MatrixX3d M(Eigen::Index(rows.size()), 3);
  for (std::size_t r = 0; r < rows.size(); ++r) M.row(Eigen::Index(r)) = rows[r].transpose();
  return M;
}

AffineMap fitGroupMap(const BoneGroupMap& group, const MatrixX3d& P, const MatrixX3d& Q, const Eigen::VectorXd& weights,
                      const Plane& referencePlane, const Plane& targetPlane) {
  if (group.symmetric) return fitSymmetricAffineMap(P, Q, weights, referencePlane, targetPlane);
  return group.longBones ? fitLongBoneMap(P, Q, weights) : fitAffineMap(P, Q, weights);
}

// Rule R6 in the bone registration: Dicko et al. 2013 leaves collisions to "standard collision handling routines"
// (§8). A vertex the group's map puts shallower inside the target's eroded skin than its attractor, or than
// the margin where the attractor is deeper, has its spring stiffened `insideWeightGrowth`-fold, up to
// `insideMaxWeight`, and the map is fitted again, until no vertex is shallow below that stiffness (at most
// `insidePasses` passes). The attractors (the skin field's interpolation) lie inside the eroded skin, so
// the stiffer springs pull the map's outermost vertices in. The cap keeps a few vertices no affine map
// can bring in from taking the map over: growing without one, their springs pulled the thin body's trunk
// map 28 mm (RMS) from its attractors after 20 passes and put more vertices out than before.
AffineMap fitGroupMapInside(const BoneGroupMap& group, const MatrixX3d& P, const MatrixX3d& Q,
                            const Plane& referencePlane, const Plane& targetPlane,
                            const AnatomyTransferOptions& options) {
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(P.rows());
  AffineMap map = fitGroupMap(group, P, Q, weights, referencePlane, targetPlane);
  if (!options.targetSkinDistance) return map;
  const Grid<float>& distance = *options.targetSkinDistance;
  const double offGrid = std::numeric_limits<double>::infinity();
  const Eigen::VectorXd wanted = sampleSignedDistance(distance, Q, offGrid).cwiseMax(-options.insideMarginMm);
  for (int pass = 0; pass < options.insidePasses; ++pass) {
    const Eigen::VectorXd d = sampleSignedDistance(distance, map.apply(P), offGrid);
    const Eigen::Array<bool, Eigen::Dynamic, 1> shallow =
        d.array() > wanted.array() && weights.array() < options.insideMaxWeight;
    if (!shallow.any()) break;
    weights = shallow.select((options.insideWeightGrowth * weights).cwiseMin(options.insideMaxWeight), weights);
    map = fitGroupMap(group, P, Q, weights, referencePlane, targetPlane);
  }
  return map;
}

// The bend that brings a mapped group's vertices (`mapped`, target space; `rest`, the same rows in the
// reference) still outside the eroded skin inside (bones_warped_into_skin.h), the distances read off the
// grids: each vertex as deep as it was in the reference skin, at most the margin; one outside the
// reference's own skin (a label past the body where a scan's field of view cut it) left as it is.
InsideSkinWarp bendInside(const MatrixX3d& mapped, const MatrixX3d& rest, const AnatomyTransferOptions& options) {
  const InsideSkinWarpOptions bend;
  Eigen::VectorXd wanted = Eigen::VectorXd::Constant(rest.rows(), -bend.marginMm);
  if (options.referenceSkinDistance) {
    const Eigen::VectorXd before =
        sampleSignedDistance(*options.referenceSkinDistance, rest, std::numeric_limits<double>::infinity());
    wanted = (before.array() > 0).select(std::numeric_limits<double>::infinity(), before.cwiseMax(wanted));
  }
  const Grid<float>& eroded = *options.targetSkinDistance;
  return warpIntoSkin(mapped, [&eroded](const MatrixX3d& P) { return sampleSkinDistances(eroded, P); }, wanted, bend);
}

// The group's bones at rest as one mesh (#V by 3 over the group's tissues in order).
TriMesh groupMesh(const BoneGroupMap& group, const ReferenceAnatomy& reference, const std::vector<MatrixX3d>& restBones) {
  TriMesh mesh;
  for (const int t : group.tissues) {
    TriMesh part;
    part.V = restBones[std::size_t(t)];
    part.F = reference.tissues[std::size_t(t)].mesh.F;
    mesh = mesh.V.rows() ? concatenate(mesh, part) : part;
  }
  return mesh;
}

// AnatomyTransferOptions::boneTargets: the group's map refined by ICP to its target points, its attractors
// (P, Q) weighing `boneTargetAttractorShare` of the points in all.
void fitGroupToTarget(BoneGroupMap& group, const TriMesh& rest, const MatrixX3d& targets, const MatrixX3d& P,
                      const MatrixX3d& Q, const Plane& referencePlane, const Plane& targetPlane,
                      const AnatomyTransferOptions& options) {
  const Eigen::Index n = targets.rows(), m = P.rows();
  MatrixX3d from(n + m, 3), to(n + m, 3);
  from.bottomRows(m) = P;
  to.topRows(n) = targets;
  to.bottomRows(m) = Q;
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n + m);
  weights.tail(m).setConstant(options.boneTargetAttractorShare * double(n) / double(std::max<Eigen::Index>(m, 1)));
  const auto pair = [&](double& rms) {
    const std::vector<ClosestPoint> closest = TriangleTree(group.map.apply(rest.V), rest.F).closest(targets);
    double sum = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const ClosestPoint& c = closest[std::size_t(i)];
      from.row(i).setZero();
      for (int k = 0; k < 3; ++k) from.row(i) += c.barycentric[k] * rest.V.row(rest.F(c.face, k));
      sum += c.squaredDistance;
    }
    rms = std::sqrt(sum / double(n));
  };
  pair(group.targetRmsBeforeMm);
  double rms = group.targetRmsBeforeMm;
  for (int iteration = 0; iteration < options.boneTargetIterations; ++iteration) {
    group.map = fitGroupMap(group, from, to, weights, referencePlane, targetPlane);
    const double previous = rms;
    pair(rms);
    if (previous - rms < 1e-3 * previous) break;
  }
  group.targetRmsAfterMm = rms;
}

// Step 2: the affine maps of the bone groups, attracted to their interpolated positions.
// Each bone is attracted by its vertices deep inside the body, where the interpolated field is defined;
// a bone with fewer than 4 of them (one outside the skin) by all of its vertices.
void registerBones(const ReferenceAnatomy& reference, const Grid<std::uint8_t>& inside,
                   const std::vector<MatrixX3d>& restBones, const std::vector<MatrixX3d>& interpolated,
                   const AnatomyTransferOptions& options, std::vector<BoneGroupMap>& groups, Plane& targetPlane) {
  std::vector<MatrixX3d> attractedRest(restBones.size()), attractors(restBones.size());
  for (std::size_t t = 0; t < restBones.size(); ++t) {
    std::vector<Eigen::Vector3d> points, values;
    appendDeepRows(inside, restBones[t], interpolated[t], points, values);
    attractedRest[t] = points.size() >= 4 ? toMatrix(points) : restBones[t];
    attractors[t] = points.size() >= 4 ? toMatrix(values) : interpolated[t];
  }
  std::vector<const MatrixX3d*> symmetricRest, symmetricMoved;
  for (const BoneGroupMap& group : groups)
    if (group.symmetric)
      for (const int t : group.tissues) symmetricRest.push_back(&attractedRest[t]), symmetricMoved.push_back(&attractors[t]);
  targetPlane = symmetricRest.empty()
                    ? reference.sagittal
                    : mapPlane(fitAffineMap(stackRows(symmetricRest), stackRows(symmetricMoved)), reference.sagittal);
  for (BoneGroupMap& group : groups) {
    const MatrixX3d P = groupVertices(group, attractedRest), Q = groupVertices(group, attractors);
    group.map = fitGroupMapInside(group, P, Q, reference.sagittal, targetPlane, options);
    const auto target = options.boneTargets.find(group.group);
    if (target != options.boneTargets.end() && target->second.rows() >= 4)
      fitGroupToTarget(group, groupMesh(group, reference, restBones), target->second, P, Q, reference.sagittal,
                       targetPlane, options);
    group.rmsToAttractorMm = std::sqrt((group.map.apply(P) - Q).rowwise().squaredNorm().mean());
    if (options.targetSkinDistance) {
      const MatrixX3d rest = groupVertices(group, restBones);
      group.bend = bendInside(group.map.apply(rest), rest, options);
    }
  }
}

}  // namespace

TransferredAnatomy transferAnatomy(const ReferenceAnatomy& reference, const MatrixX3d& targetSkin,
                                   const Grid<std::uint8_t>& referenceInside,
                                   const AnatomyTransferOptions& options) {
  reference.validate(reference.name);
  if (targetSkin.rows() != reference.skin.V.rows())
    throw BadInput("", "anatomy transfer: the target skin has " + std::to_string(targetSkin.rows()) +
                           " vertices, the reference skin " + std::to_string(reference.skin.V.rows()));
  if (!targetSkin.allFinite()) throw BadInput("", "anatomy transfer: a target skin vertex is not finite");
  TransferredAnatomy result;

  auto start = std::chrono::steady_clock::now();
  // Cut skin is not skin: where a scan's field of view cut the body, the body goes on, so those vertices
  // fix nothing and the field runs out to the cut freely (zero flux) instead of following how the
  // registration happened to slide them over the flat cap.
  std::vector<std::uint8_t> cut(std::size_t(reference.skin.V.rows()), 0);
  for (const int v : reference.skinCutVertices) cut[std::size_t(v)] = 1;
  std::vector<Eigen::Vector3d> fixedPoints, fixedValues;
  for (Eigen::Index r = 0; r < targetSkin.rows(); ++r)
    if (!cut[std::size_t(r)])
      fixedPoints.push_back(reference.skin.V.row(r).transpose()),
          fixedValues.push_back((targetSkin.row(r) - reference.skin.V.row(r)).transpose());
  result.skinField = interpolateDisplacements(referenceInside, toMatrix(fixedPoints), toMatrix(fixedValues), options.field);
  std::vector<MatrixX3d> rest;
  for (const ReferenceTissue& tissue : reference.tissues) {
    rest.push_back(tissue.mesh.V);
    result.interpolated.push_back(result.skinField.displace(tissue.mesh.V));
  }
  result.secondsSkinField = secondsSince(start);

  start = std::chrono::steady_clock::now();
  result.boneGroups = boneGroups(reference);
  registerBones(reference, referenceInside, rest, result.interpolated, options, result.boneGroups, result.sagittal);
  std::vector<int> mapOfTissue(reference.tissues.size(), -1);
  for (int g = 0; g < int(result.boneGroups.size()); ++g)
    for (const int t : result.boneGroups[g].tissues) mapOfTissue[t] = g;
  result.secondsBones = secondsSince(start);

  start = std::chrono::steady_clock::now();
  const std::vector<std::vector<bool>> atJoints =
      rowsAtJoints(result.boneGroups, rest, referenceInside.geometry, options.jointFreeCells);
  result.tissues.resize(reference.tissues.size());
  for (const BoneGroupMap& group : result.boneGroups)
    for (const int t : group.tissues) {
      result.tissues[t] = group.place(rest[t]);
      appendDeepRows(referenceInside, rest[t], result.tissues[t] - rest[t], fixedPoints, fixedValues, atJoints[t]);
    }
  DisplacementFieldOptions finalOptions = options.field;
  finalOptions.unfoldPasses = options.finalUnfoldPasses;
  result.finalField = interpolateDisplacements(referenceInside, toMatrix(fixedPoints), toMatrix(fixedValues),
                                               finalOptions, &result.skinField);
  for (int t = 0; t < int(reference.tissues.size()); ++t)
    if (mapOfTissue[t] < 0) result.tissues[t] = result.finalField.displace(rest[t]);
  std::map<std::string, int> tissueIndex;
  for (int t = 0; t < int(reference.tissues.size()); ++t) tissueIndex[reference.tissues[t].name] = t;
  result.points.resize(Eigen::Index(reference.points.size()), 3);
  for (std::size_t p = 0; p < reference.points.size(); ++p) {
    const ReferencePoint& point = reference.points[p];
    const auto it = tissueIndex.find(point.tissue);
    const int group = it == tissueIndex.end() ? -1 : mapOfTissue[it->second];
    result.points.row(Eigen::Index(p)) = (group >= 0 ? Eigen::Vector3d(result.boneGroups[group].place(point.position.transpose()).transpose())
                                                     : point.position + result.finalField.displacementAt(point.position))
                                             .transpose();
  }
  result.secondsFinalField = secondsSince(start);
  return result;
}

}  // namespace vesalius::transfer
