// The anatomical rules measured on a whole anatomy (anatomy_rules.h).
#include "vesalius/transfer/anatomy_rules.h"

#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/meshing/body_distance.h"
#include "vesalius/meshing/winding_number.h"
#include "vesalius/transfer/anatomy_checks.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <utility>

namespace vesalius::transfer {
namespace {

using Clock = std::chrono::steady_clock;

// The reference tissue whose mesh `tissue` carries (same name, triangles and vertex count), or -1.
int carriedReferenceTissue(const ReferenceAnatomy& reference, const std::map<std::string, int>& byName,
                           const ReferenceTissue& tissue) {
  const auto it = byName.find(tissue.name);
  if (it == byName.end()) return -1;
  const TriMesh& r = reference.tissues[std::size_t(it->second)].mesh;
  return r.V.rows() == tissue.mesh.V.rows() && r.F.rows() == tissue.mesh.F.rows() && r.F == tissue.mesh.F ? it->second
                                                                                                        : -1;
}

// A body (skin with its cavities) to measure "inside" against: the caller's grids or one made here.
class Body {
 public:
  Body(const TriMesh& skin, const std::vector<int>& cutVertices, const Grid<float>* distance,
       const Grid<std::uint8_t>* cavities)
      : skin_(skin), tree_(skin.V, skin.F), cut_(std::size_t(skin.V.rows()), false) {
    for (const int v : cutVertices)
      if (v >= 0 && v < skin.V.rows()) cut_[std::size_t(v)] = true;
    if (!distance) {
      made_ = meshing::bodySignedDistance(skin);
      distance_ = &made_->signedDistance;
      cavities_ = &made_->cavities;
    } else {
      distance_ = distance;
      cavities_ = cavities;
    }
  }

  // Signed distance (mm, negative inside) at each row of V; off the grid, the distance to the skin's
  // triangles, outside.
  Eigen::VectorXd signedDistance(const MatrixX3d& V) const {
    Eigen::VectorXd d = sampleSignedDistance(*distance_, V, std::numeric_limits<double>::quiet_NaN());
    for (Eigen::Index r = 0; r < V.rows(); ++r)
      if (std::isnan(d[r])) d[r] = std::sqrt(tree_.closest(Eigen::Vector3d(V.row(r).transpose())).squaredDistance);
    return d;
  }

  // Whether each row of V lies in a cavity (its nearest voxel); none without the cavities.
  std::vector<bool> inCavities(const MatrixX3d& V) const {
    std::vector<bool> in(std::size_t(V.rows()), false);
    if (!cavities_) return in;
    const GridGeometry& g = cavities_->geometry;
    for (Eigen::Index r = 0; r < V.rows(); ++r) {
      const Eigen::Vector3i v = g.worldToIndex(V.row(r).transpose()).array().round().cast<int>();
      in[std::size_t(r)] = g.contains(v.x(), v.y(), v.z()) && cavities_->at(v.x(), v.y(), v.z());
    }
    return in;
  }

  // Of the rows of V with distance > 0, how many lie nearest a skin triangle with a cut vertex: outside
  // through a scan's cut, not through the skin.
  std::vector<bool> atCut(const MatrixX3d& V, const Eigen::VectorXd& distance) const {
    std::vector<bool> at(std::size_t(V.rows()), false);
    if (std::find(cut_.begin(), cut_.end(), true) == cut_.end()) return at;
    std::vector<Eigen::Index> outside;
    for (Eigen::Index r = 0; r < V.rows(); ++r)
      if (distance[r] > 0) outside.push_back(r);
    if (outside.empty()) return at;
    const std::vector<ClosestPoint> closest = tree_.closest(MatrixX3d(V(outside, Eigen::all)));
    for (std::size_t i = 0; i < outside.size(); ++i) {
      const int f = closest[i].face;
      at[std::size_t(outside[i])] = cut_[std::size_t(skin_.F(f, 0))] || cut_[std::size_t(skin_.F(f, 1))] ||
                                    cut_[std::size_t(skin_.F(f, 2))];
    }
    return at;
  }

 private:
  const TriMesh& skin_;
  TriangleTree tree_;
  std::vector<bool> cut_;
  std::optional<meshing::BodyDistance> made_;
  const Grid<float>* distance_ = nullptr;
  const Grid<std::uint8_t>* cavities_ = nullptr;
};

void checkSkin(const TriMesh& skin, const std::string& which) {
  if (skin.V.rows() == 0 || skin.F.rows() == 0) throw BadInput("", "anatomy rules: the " + which + " skin is empty");
}

void measureOutside(const ReferenceAnatomy& reference, const ReferenceAnatomy& transferred,
                    const AnatomyRulesOptions& o, AnatomyRules& rules) {
  OutsideRule& out = rules.outside;
  out.measured = true;
  checkSkin(transferred.skin, "transferred");
  const Body body(transferred.skin, transferred.skinCutVertices, o.skinDistance, o.skinCavities);
  // The reference's body, when some tissue carries its mesh: the same as the transferred one for the same
  // skin and grids (a reference checked against itself).
  std::optional<Body> referenceBody;
  const bool carried = std::any_of(rules.tissues.begin(), rules.tissues.end(),
                                   [](const TissueRules& row) { return row.referenceTissue >= 0; });
  const bool sameBody = o.referenceSkinDistance == o.skinDistance && o.referenceSkinCavities == o.skinCavities &&
                        reference.skin.V.rows() == transferred.skin.V.rows() &&
                        reference.skin.F.rows() == transferred.skin.F.rows() && reference.skin.V == transferred.skin.V &&
                        reference.skin.F == transferred.skin.F && reference.skinCutVertices == transferred.skinCutVertices;
  if (carried && !sameBody) {
    checkSkin(reference.skin, "reference");
    referenceBody.emplace(reference.skin, reference.skinCutVertices, o.referenceSkinDistance, o.referenceSkinCavities);
  }
  const Body& referenceSide = referenceBody ? *referenceBody : body;
  for (std::size_t t = 0; t < transferred.tissues.size(); ++t) {
    const MatrixX3d& V = transferred.tissues[t].mesh.V;
    TissueRules& row = rules.tissues[t];
    const Eigen::VectorXd after = body.signedDistance(V);
    const std::vector<bool> cut = body.atCut(V, after), cavity = body.inCavities(V);
    Eigen::VectorXd before;
    std::vector<bool> cutBefore, cavityBefore;
    if (row.referenceTissue >= 0) {
      const MatrixX3d& R = reference.tissues[std::size_t(row.referenceTissue)].mesh.V;
      before = referenceSide.signedDistance(R);
      cutBefore = referenceSide.atCut(R, before);
      cavityBefore = referenceSide.inCavities(R);
    }
    row.vertices = V.rows();
    for (Eigen::Index r = 0; r < V.rows(); ++r) {
      const std::size_t i = std::size_t(r);
      row.inCavities += cavity[i];
      if (after[r] > 0) {
        ++row.outside;
        row.outsideAtCut += cut[i];
        if (after[r] > row.outsideWorstMm) row.outsideWorstMm = after[r];
        if (after[r] > out.worstMm) out.worstMm = after[r], out.worstTissue = int(t), out.worstAt = V.row(r).transpose();
      }
      if (row.referenceTissue < 0) continue;
      row.referenceInCavities += cavityBefore[i];
      if (before[r] > 0) {
        ++row.referenceOutside;
        out.referenceOutsideAtCut += cutBefore[i];
      } else if (after[r] > 0) {
        ++row.pushedOut;
        row.pushedOutDeep += before[r] <= -o.deepMm;
        out.pushedOutWorstMm = std::max(out.pushedOutWorstMm, after[r]);
      }
    }
    out.vertices += row.vertices;
    out.outside += row.outside;
    out.outsideAtCut += row.outsideAtCut;
    out.inCavities += row.inCavities;
    if (row.referenceTissue >= 0) {
      out.referenceVertices += row.vertices;
      out.referenceOutside += row.referenceOutside;
      out.referenceInCavities += row.referenceInCavities;
      out.pushedOut += row.pushedOut;
      out.pushedOutDeep += row.pushedOutDeep;
    }
  }
  out.holds = out.outside == out.outsideAtCut;
}

// One mesh of the tissues `members` (indices into anatomy.tissues), vertices from `vertices(t)`.
template <class Vertices>
TriMesh joined(const ReferenceAnatomy& anatomy, const std::vector<int>& members, Vertices vertices) {
  TriMesh all;
  for (const int t : members) {
    TriMesh part;
    part.V = vertices(t);
    part.F = anatomy.tissues[std::size_t(t)].mesh.F;
    all = all.V.rows() ? concatenate(all, part) : part;
  }
  return all;
}

void measureSymmetry(const ReferenceAnatomy& reference, const ReferenceAnatomy& transferred,
                     const AnatomyRulesOptions& o, AnatomyRules& rules) {
  SymmetryRule& out = rules.symmetry;
  out.measured = true;
  std::map<std::string, std::size_t> groupIndex;
  for (std::size_t t = 0; t < transferred.tissues.size(); ++t) {
    const ReferenceTissue& tissue = transferred.tissues[t];
    if (!tissue.symmetric || tissue.kind != TissueKind::Bone || tissue.mesh.F.rows() == 0) continue;
    const std::string key = tissue.group.empty() ? tissue.name : tissue.group;
    const auto [it, inserted] = groupIndex.emplace(key, out.groups.size());
    if (inserted) out.groups.push_back({key, {}, 0, kNotMeasured});
    out.groups[it->second].tissues.push_back(int(t));
  }
  double worst = -std::numeric_limits<double>::infinity();
  for (SymmetricGroup& g : out.groups) {
    const TriMesh now = joined(transferred, g.tissues, [&](int t) { return transferred.tissues[std::size_t(t)].mesh.V; });
    g.asymmetryMm = mirrorAsymmetry(now.V, now.F, transferred.sagittal);
    const bool carried = std::all_of(g.tissues.begin(), g.tissues.end(),
                                     [&](int t) { return rules.tissues[std::size_t(t)].referenceTissue >= 0; });
    if (carried) {
      const TriMesh rest = joined(transferred, g.tissues, [&](int t) {
        return reference.tissues[std::size_t(rules.tissues[std::size_t(t)].referenceTissue)].mesh.V;
      });
      g.referenceAsymmetryMm = mirrorAsymmetry(rest.V, rest.F, reference.sagittal);
    }
    const double excess = g.asymmetryMm - (carried ? g.referenceAsymmetryMm : 0.0);
    if (excess > worst) worst = excess, out.worstGroup = g.group;
  }
  out.worstExcessMm = out.groups.empty() ? 0.0 : worst;
  out.holds = out.worstExcessMm <= o.symmetryToleranceMm;
}

void measureStraightness(const ReferenceAnatomy& reference, const ReferenceAnatomy& transferred,
                         const AnatomyRulesOptions& o, AnatomyRules& rules) {
  StraightnessRule& out = rules.straightness;
  out.measured = true;
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < transferred.tissues.size(); ++t) {
    const ReferenceTissue& tissue = transferred.tissues[t];
    TissueRules& row = rules.tissues[t];
    if (row.referenceTissue < 0 || tissue.kind != TissueKind::Bone || tissue.symmetric) continue;
    const MatrixX3d& rest = reference.tissues[std::size_t(row.referenceTissue)].mesh.V;
    if (rest.rows() < 8 || !isLongBone(rest)) continue;
    row.referenceCentreLineDeviation = centreLineDeviation(rest, rest);
    row.centreLineDeviation = centreLineDeviation(rest, tissue.mesh.V);
    out.bones.push_back({int(t), row.centreLineDeviation, row.referenceCentreLineDeviation});
    const double excess = row.centreLineDeviation - row.referenceCentreLineDeviation;
    if (excess > worst) worst = excess, out.worstTissue = int(t);
  }
  out.worstExcess = out.bones.empty() ? 0.0 : worst;
  out.holds = out.worstExcess <= o.straightnessTolerance;
}

// The pairs of `tissues` (indices into anatomy.tissues, each with triangles) whose boxes overlap, with
// the deepest vertex of either inside the other, keyed by (smaller, larger) index. `boxPairs` counts the
// candidate pairs.
std::map<std::pair<int, int>, Interpenetration> interpenetrations(const ReferenceAnatomy& anatomy,
                                                                   const std::vector<int>& tissues, long& boxPairs) {
  std::vector<Eigen::AlignedBox3d> boxes(anatomy.tissues.size());
  for (const int t : tissues) boxes[std::size_t(t)] = boundingBox(anatomy.tissues[std::size_t(t)].mesh.V);
  boxPairs = 0;
  std::map<std::pair<int, int>, Interpenetration> pairs;
  for (const int b : tissues) {
    // Every vertex of another tissue inside b's box is a candidate: one winding-number pass and one
    // closest-point pass over b for all of them.
    const TriMesh& B = anatomy.tissues[std::size_t(b)].mesh;
    const Eigen::AlignedBox3d& box = boxes[std::size_t(b)];
    std::vector<std::pair<int, Eigen::Index>> candidates;
    for (const int a : tissues) {
      if (a == b || !boxes[std::size_t(a)].intersects(box)) continue;
      if (a < b) ++boxPairs;
      const MatrixX3d& A = anatomy.tissues[std::size_t(a)].mesh.V;
      for (Eigen::Index r = 0; r < A.rows(); ++r)
        if (box.contains(A.row(r).transpose())) candidates.emplace_back(a, r);
    }
    if (candidates.empty()) continue;
    MatrixX3d P(Eigen::Index(candidates.size()), 3);
    for (std::size_t i = 0; i < candidates.size(); ++i)
      P.row(Eigen::Index(i)) = anatomy.tissues[std::size_t(candidates[i].first)].mesh.V.row(candidates[i].second);
    for (const meshing::PointInside& in : meshing::pointsInside(B.V, B.F, P)) {
      const int a = candidates[std::size_t(in.row)].first;
      Interpenetration& pair = pairs[{std::min(a, b), std::max(a, b)}];
      pair.a = std::min(a, b), pair.b = std::max(a, b);
      ++pair.vertices;
      const double depth = std::sqrt(in.closest.squaredDistance);
      if (depth >= pair.depthMm) pair.depthMm = depth, pair.at = P.row(in.row).transpose();
    }
  }
  return pairs;
}

void measureInterpenetration(const ReferenceAnatomy& reference, const ReferenceAnatomy& transferred,
                             const AnatomyRulesOptions& o, AnatomyRules& rules) {
  InterpenetrationRule& out = rules.interpenetration;
  out.measured = true;
  std::vector<int> measured, carried;
  std::map<int, int> fromReference;  // reference tissue -> transferred tissue, for the carried ones
  for (std::size_t t = 0; t < transferred.tissues.size(); ++t) {
    const TriMesh& m = transferred.tissues[t].mesh;
    TissueRules& row = rules.tissues[t];
    row.closed = m.F.rows() > 0 && countEdges(m.F).boundary == 0;
    if (m.F.rows() == 0 || m.V.rows() == 0) {
      out.skippedTissues.push_back(int(t));
      continue;
    }
    measured.push_back(int(t));
    if (!row.closed) out.openTissues.push_back(int(t));
    if (row.referenceTissue >= 0) carried.push_back(row.referenceTissue), fromReference[row.referenceTissue] = int(t);
  }
  const std::map<std::pair<int, int>, Interpenetration> now = interpenetrations(transferred, measured, out.boxPairs);
  // The reference's own, for the pairs that both carry its mesh (bones of an OpenSim model overlap at
  // joints already in the reference).
  long referenceBoxPairs = 0;
  std::map<std::pair<int, int>, double> before;
  for (const auto& [key, pair] : interpenetrations(reference, carried, referenceBoxPairs)) {
    const int a = fromReference.at(pair.a), b = fromReference.at(pair.b);
    before[{std::min(a, b), std::max(a, b)}] = pair.depthMm;
  }
  for (const auto& [key, found] : now) {
    Interpenetration pair = found;
    if (rules.tissues[std::size_t(pair.a)].referenceTissue >= 0 && rules.tissues[std::size_t(pair.b)].referenceTissue >= 0) {
      const auto it = before.find(key);
      pair.referenceDepthMm = it == before.end() ? 0.0 : it->second;
    }
    out.pairs.push_back(pair);
    for (const int t : {pair.a, pair.b}) {
      TissueRules& row = rules.tissues[std::size_t(t)];
      if (row.interpenetrates < 0 || pair.depthMm > row.interpenetrationMm)
        row.interpenetrationMm = pair.depthMm, row.interpenetrates = t == pair.a ? pair.b : pair.a;
    }
  }
  std::stable_sort(out.pairs.begin(), out.pairs.end(),
                   [](const Interpenetration& x, const Interpenetration& y) { return x.excessMm() > y.excessMm(); });
  for (const Interpenetration& pair : out.pairs) out.worstMm = std::max(out.worstMm, pair.depthMm);
  out.worstExcessMm = out.pairs.empty() ? 0.0 : out.pairs.front().excessMm();
  out.holds = out.worstExcessMm <= o.interpenetrationToleranceMm;
}

}  // namespace

AnatomyRules checkAnatomyRules(const ReferenceAnatomy& reference, const ReferenceAnatomy& transferred,
                               const DisplacementField* field, const AnatomyRulesOptions& options) {
  AnatomyRules rules;
  std::map<std::string, int> byName;
  for (std::size_t t = 0; t < reference.tissues.size(); ++t) byName.emplace(reference.tissues[t].name, int(t));
  rules.tissues.resize(transferred.tissues.size());
  for (std::size_t t = 0; t < transferred.tissues.size(); ++t) {
    rules.tissues[t].referenceTissue = carriedReferenceTissue(reference, byName, transferred.tissues[t]);
    rules.tissues[t].vertices = transferred.tissues[t].mesh.V.rows();
  }
  auto start = Clock::now();
  const auto end = [&](const char* rule) {
    const auto now = Clock::now();
    rules.stageSeconds.emplace_back(rule, std::chrono::duration<double>(now - start).count());
    start = now;
  };
  if (options.outside) measureOutside(reference, transferred, options, rules), end("outside");
  if (options.folds && field) {
    rules.folds.measured = true;
    rules.folds.jacobian = jacobianDeterminant(*field);
    rules.folds.holds = rules.folds.jacobian.nonPositiveCells == 0;
    end("folds");
  }
  if (options.symmetry) measureSymmetry(reference, transferred, options, rules), end("symmetry");
  if (options.straightness) measureStraightness(reference, transferred, options, rules), end("straightness");
  if (options.interpenetration) measureInterpenetration(reference, transferred, options, rules), end("interpenetration");
  return rules;
}

}  // namespace vesalius::transfer
