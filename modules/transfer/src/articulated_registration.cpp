// Skin registration with an articulated stage (articulated_registration.h).
#include "vesalius/transfer/articulated_registration.h"

#include "skin_correspondences.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"

#include <Eigen/SVD>

#include <algorithm>
#include <map>
#include <string>

namespace vesalius::transfer {

namespace {

// Step 2, first half: the part of every skin vertex, by its closest bone.
void assignParts(const ReferenceAnatomy& reference, SkinParts& parts) {
  parts.names = {"trunk"};
  std::map<std::string, int> index{{"trunk", 0}};
  TriMesh bones;
  std::vector<int> partOfFace;
  for (const ReferenceTissue& tissue : reference.tissues) {
    if (tissue.kind != TissueKind::Bone) continue;
    const std::string name = tissue.symmetric ? "trunk" : tissue.group.empty() ? tissue.name : tissue.group;
    const auto [it, inserted] = index.emplace(name, int(parts.names.size()));
    if (inserted) parts.names.push_back(name);
    bones = bones.V.rows() ? concatenate(bones, tissue.mesh) : tissue.mesh;
    partOfFace.insert(partOfFace.end(), std::size_t(tissue.mesh.F.rows()), it->second);
  }
  parts.partOfVertex.assign(std::size_t(reference.skin.V.rows()), 0);
  if (bones.F.rows() == 0) return;
  const std::vector<ClosestPoint> closest = TriangleTree(bones.V, bones.F).closest(reference.skin.V);
  for (std::size_t v = 0; v < closest.size(); ++v) parts.partOfVertex[v] = partOfFace[std::size_t(closest[v].face)];
}

// The skin edges between parts a and b (count[a][b], each edge counted from both of its faces) and the sum
// of their midpoints (midpoints[a][b]).
struct PartBorders {
  std::vector<std::vector<int>> count;
  std::vector<std::vector<Eigen::Vector3d>> midpoints;
};

PartBorders partBorders(const MatrixX3d& V, const MatrixX3i& F, const SkinParts& parts) {
  const std::size_t n = parts.names.size();
  PartBorders borders{std::vector<std::vector<int>>(n, std::vector<int>(n, 0)),
                      std::vector<std::vector<Eigen::Vector3d>>(n, std::vector<Eigen::Vector3d>(n, Eigen::Vector3d::Zero()))};
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3), pa = parts.partOfVertex[a], pb = parts.partOfVertex[b];
      if (pa == pb) continue;
      const Eigen::Vector3d mid = 0.5 * (V.row(a) + V.row(b)).transpose();
      ++borders.count[pa][pb], ++borders.count[pb][pa];
      borders.midpoints[pa][pb] += mid, borders.midpoints[pb][pa] += mid;
    }
  return borders;
}

// Step 2, second half: the tree of parts by shared skin edges, breadth first from the trunk, and the joints.
void joinParts(const MatrixX3d& V, const MatrixX3i& F, SkinParts& parts) {
  const int count = int(parts.names.size());
  const PartBorders borders = partBorders(V, F, parts);
  const std::vector<std::vector<int>>& border = borders.count;
  const std::vector<std::vector<Eigen::Vector3d>>& midpoints = borders.midpoints;
  parts.parent.assign(count, -1);
  parts.joint.assign(count, Eigen::Vector3d::Zero());
  parts.order = {0};
  std::vector<char> reached(count, 0);
  reached[0] = 1;
  for (std::size_t level = 0; level < parts.order.size();) {
    const std::size_t levelEnd = parts.order.size();
    for (int p = 0; p < count; ++p) {
      if (reached[p]) continue;
      int best = -1;
      for (std::size_t i = level; i < levelEnd; ++i) {
        const int q = parts.order[i];
        if (border[p][q] > 0 && (best < 0 || border[p][q] > border[p][best])) best = q;
      }
      if (best < 0) continue;
      parts.parent[p] = best;
      parts.joint[p] = midpoints[p][best] / double(border[p][best]);
      parts.order.push_back(p);
    }
    for (std::size_t i = levelEnd; i < parts.order.size(); ++i) reached[parts.order[i]] = 1;
    level = levelEnd;
  }
}

// Two parts with the same parent that share a border (the skin over radius and ulna, over talus and
// calcaneus) are one segment of the limb: the second is merged into the first. Whether any were merged.
bool mergeTouchingSiblings(const MatrixX3d& V, const MatrixX3i& F, SkinParts& parts) {
  const PartBorders borders = partBorders(V, F, parts);
  const int count = int(parts.names.size());
  for (int a = 1; a < count; ++a)
    for (int b = a + 1; b < count; ++b) {
      if (parts.parent[a] < 0 || parts.parent[a] != parts.parent[b] || borders.count[a][b] == 0) continue;
      parts.names[a] += "+" + parts.names[b];
      parts.names.erase(parts.names.begin() + b);
      for (int& p : parts.partOfVertex) p = p == b ? a : p > b ? p - 1 : p;
      return true;
    }
  return false;
}

void checkOptions(const ArticulatedRegistrationOptions& o) {
  if (o.passes < 0) throw UsageError("articulated registration: passes must not be negative");
  if (o.blendIterations < 0) throw UsageError("articulated registration: blend iterations must not be negative");
}

void checkParts(const SkinParts& parts, Eigen::Index vertexCount) {
  const int count = int(parts.names.size());
  const bool sizes = Eigen::Index(parts.partOfVertex.size()) == vertexCount && count > 0 &&
                     int(parts.parent.size()) == count && int(parts.joint.size()) == count;
  if (!sizes) throw BadInput("", "articulated registration: the skin parts do not fit the skin");
  for (const int p : parts.partOfVertex)
    if (p < 0 || p >= count) throw BadInput("", "articulated registration: a skin vertex names no part");
  for (const int p : parts.order)
    if (p < 0 || p >= count || (p != parts.order.front() && (parts.parent[p] < 0 || parts.parent[p] >= count)))
      throw BadInput("", "articulated registration: the parts' order names no part or a part without parent");
}

// The x -> c + s R (x − c) minimising Σ w |c + s R (x − c) − y|² (Kabsch about a fixed point c).
SimilarityTransform fitAboutPoint(const MatrixX3d& from, const MatrixX3d& to, const Eigen::VectorXd& w,
                                       const Eigen::Vector3d& c, bool allowScale) {
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  double spread = 0;
  for (Eigen::Index r = 0; r < from.rows(); ++r) {
    const Eigen::Vector3d x = from.row(r).transpose() - c, y = to.row(r).transpose() - c;
    H += w[r] * x * y.transpose();
    spread += w[r] * x.squaredNorm();
  }
  SimilarityTransform t;
  if (!(spread > 0)) return t;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const double sign = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  t.rotation = svd.matrixV() * Eigen::Vector3d(1, 1, sign).asDiagonal() * svd.matrixU().transpose();
  if (allowScale) t.scale = std::max((t.rotation * H).trace() / spread, 1e-3);
  t.translation = c - t.scale * t.rotation * c;
  return t;
}

// Every vertex moved by its own part's transform (no blending: the parts' fits see their own vertices).
MatrixX3d posedRigidly(const MatrixX3d& Q, const std::vector<int>& partOfVertex,
                       const std::vector<SimilarityTransform>& T) {
  MatrixX3d X(Q.rows(), 3);
  for (Eigen::Index v = 0; v < Q.rows(); ++v) X.row(v) = T[partOfVertex[v]].apply(Eigen::Vector3d(Q.row(v))).transpose();
  return X;
}

// Which parts are in the subtree of `root` (itself included).
std::vector<char> subtree(const SkinParts& parts, int root) {
  std::vector<char> in(parts.names.size(), 0);
  in[root] = 1;
  for (const int p : parts.order)  // parents come before children
    if (parts.parent[p] >= 0 && in[parts.parent[p]]) in[p] = 1;
  return in;
}

// The correspondences of the vertices whose part is selected, as point rows.
void selectedPairs(const MatrixX3d& X, const std::vector<detail::Pair>& pairs, const std::vector<int>& partOfVertex,
                   const std::vector<char>& selected, MatrixX3d& from, MatrixX3d& to, Eigen::VectorXd& w) {
  std::vector<const detail::Pair*> kept;
  for (const detail::Pair& p : pairs)
    if (selected[partOfVertex[p.vertices[0]]] && selected[partOfVertex[p.vertices[1]]] &&
        selected[partOfVertex[p.vertices[2]]])
      kept.push_back(&p);
  from.resize(Eigen::Index(kept.size()), 3), to.resize(Eigen::Index(kept.size()), 3), w.resize(Eigen::Index(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i) {
    from.row(Eigen::Index(i)) = detail::sourcePoint(X, *kept[i]).transpose();
    to.row(Eigen::Index(i)) = kept[i]->target.transpose();
    w[Eigen::Index(i)] = kept[i]->weight;
  }
}

// Step 3: the parts' transforms. Each pass takes fresh correspondences of the whole skin, then fits the
// parts in order, parents before children, each from the pairs' current source points.
std::vector<SimilarityTransform> articulate(const MatrixX3d& Q, const MatrixX3i& Fs, const SkinParts& parts,
                                                 const detail::Target& target, const ArticulatedRegistrationOptions& o) {
  std::vector<SimilarityTransform> T(parts.names.size());
  std::vector<std::vector<char>> moved, own;
  for (const int part : parts.order) {
    moved.push_back(subtree(parts, part));
    own.emplace_back(parts.names.size(), 0);
    own.back()[part] = 1;
  }
  for (int it = 0; it < o.passes; ++it) {
    const MatrixX3d X = posedRigidly(Q, parts.partOfVertex, T);
    const std::vector<detail::Pair> pairs =
        detail::correspondences(X, Fs, target.tree.closest(X), target, {}, o.registration);
    for (std::size_t i = 0; i < parts.order.size(); ++i) {
      const int part = parts.order[i];
      const bool root = i == 0;
      MatrixX3d from, to;
      Eigen::VectorXd w;
      selectedPairs(posedRigidly(Q, parts.partOfVertex, T), pairs, parts.partOfVertex, root ? own[i] : moved[i], from,
                    to, w);
      if (from.rows() < 3) continue;
      const SimilarityTransform step =
          root ? fitSimilarity(from, to, w, false)
               : fitAboutPoint(from, to, w, T[parts.parent[part]].apply(parts.joint[part]), o.partScale);
      for (std::size_t p = 0; p < T.size(); ++p)
        if (moved[i][p]) T[p] = detail::compose(step, T[p]);
    }
  }
  return T;
}

// Step 4: linear blend skinning with the part weights smoothed over the skin.
MatrixX3d blendParts(const MatrixX3d& Q, const MatrixX3i& Fs, const SkinParts& parts,
                     const std::vector<SimilarityTransform>& T, int blendIterations) {
  const Eigen::Index n = Q.rows(), count = Eigen::Index(parts.names.size());
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, count);
  for (Eigen::Index v = 0; v < n; ++v) W(v, parts.partOfVertex[v]) = 1;
  const std::vector<std::vector<int>> neighbours = detail::skinNeighbours(n, Fs);
  for (int it = 0; it < blendIterations; ++it) {
    Eigen::MatrixXd next = W;
    for (Eigen::Index v = 0; v < n; ++v) {
      for (const int u : neighbours[v]) next.row(v) += W.row(u);
      next.row(v) /= double(neighbours[v].size() + 1);
    }
    W = std::move(next);
  }
  MatrixX3d X = MatrixX3d::Zero(n, 3);
  for (Eigen::Index p = 0; p < count; ++p) {
    const MatrixX3d moved = T[p].apply(Q);
    X += W.col(p).asDiagonal() * moved;
  }
  return X;
}

}  // namespace

SkinParts skinPartsFromBones(const ReferenceAnatomy& reference) {
  SkinParts parts;
  assignParts(reference, parts);
  do joinParts(reference.skin.V, reference.skin.F, parts);
  while (mergeTouchingSiblings(reference.skin.V, reference.skin.F, parts));
  return parts;
}

ArticulatedRegistration registerSkinArticulated(const MatrixX3d& Vs, const MatrixX3i& Fs, const SkinParts& parts,
                                                const MatrixX3d& Vt, const MatrixX3i& Ft,
                                                const ArticulatedRegistrationOptions& options,
                                                const std::vector<SkinLandmark>& landmarks) {
  checkOptions(options);
  checkParts(parts, Vs.rows());
  const SimilarityTransform alignment = alignSkin(Vs, Fs, Vt, Ft, options.registration, landmarks);
  SkinParts aligned = parts;
  for (Eigen::Vector3d& joint : aligned.joint) joint = alignment.apply(joint);
  const MatrixX3d Q = alignment.apply(Vs);
  const detail::Target target = detail::makeTarget(Vt, Ft);
  ArticulatedRegistration result;
  result.partTransforms = articulate(Q, Fs, aligned, target, options);
  result.articulated = blendParts(Q, Fs, aligned, result.partTransforms, options.blendIterations);
  SkinRegistrationOptions deform = options.registration;
  deform.align = false;
  result.registration = registerSkin(result.articulated, Fs, Vt, Ft, deform, landmarks);
  result.registration.alignment = alignment;
  return result;
}

}  // namespace vesalius::transfer
