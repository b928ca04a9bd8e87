#include "vesalius/transfer/partial_skin_registration.h"

#include "skin_correspondences.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/transfer/surface_harmonic_extension.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

namespace vesalius::transfer {
namespace {

constexpr double kPi = 3.14159265358979323846;

void checkMesh(const MatrixX3d& V, const MatrixX3i& F, const std::string& name) {
  if (V.rows() == 0 || F.rows() == 0) throw BadInput("", "partial skin registration: the " + name + " is empty");
  TriMesh{V, F, {}, {}, {}, {}}.validate("partial skin registration " + name);
}

void checkOptions(const PartialSkinRegistrationOptions& o) {
  detail::checkOptions(o.registration);
  const auto usage = [](const std::string& what) { throw UsageError("partial skin registration: " + what); };
  if (o.alignmentStarts < 1) usage("at least one alignment start is needed");
  if (!(o.startsFrom >= 0 && o.startsFrom <= o.startsTo && o.startsTo <= 1))
    usage("the alignment starts must lie within the source's height, from <= to");
  if (o.alignIterations < 1) usage("alignment iterations must be at least 1");
  if (o.refinedStarts < 1) usage("at least one alignment start must be refined");
  if (o.refineIterations < 1) usage("refining iterations must be at least 1");
  if (!(o.settledMm > 0 && std::isfinite(o.settledMm))) usage("the settling tolerance must be > 0");
  if (o.alignmentPoints < 3) usage("the alignment needs at least 3 points per side");
  if (!(o.reciprocalToleranceMm >= 0 && std::isfinite(o.reciprocalToleranceMm)))
    usage("the reciprocal tolerance must be >= 0");
}

// The target's skin vertices (not cut) as rows, with their normals.
struct SkinSide {
  MatrixX3d V, normals;
};

SkinSide targetSkinSide(const detail::Target& target) {
  std::vector<Eigen::Index> rows;
  for (Eigen::Index v = 0; v < target.V.rows(); ++v)
    if (!target.cutVertex[std::size_t(v)]) rows.push_back(v);
  if (rows.empty()) throw BadInput("", "partial skin registration: every target vertex is on the cut");
  return {target.V(rows, Eigen::all), target.vertexNormals(rows, Eigen::all)};
}

struct Alignment {
  SimilarityTransform transform;
  Eigen::Vector3d matchedCentroid = Eigen::Vector3d::Zero();  // of the paired source skin points, rest coordinates
  double meanDistance = std::numeric_limits<double>::infinity();  // of the target's skin vertices
  double score = std::numeric_limits<double>::infinity();  // that, plus the bones' mean distance if any
};

// One kind of surface step 1 pairs: the target's points (with normals, or none for no normal test) to
// their closest points on the source's surface of that kind (rest coordinates).
struct AlignedSide {
  const MatrixX3d& sourceV;
  const MatrixX3i& sourceF;
  const MatrixX3d& target;
  const MatrixX3d* targetNormals;
};

// The pairs of one side under transform T, trimmed at three times their median distance and, with
// normals, at the normal angle: rows of rest source points and target points. meanDistance: over all
// target points.
struct SidePairs {
  MatrixX3d from, to;
  double meanDistance = 0;
};

SidePairs sidePairs(const AlignedSide& side, const SimilarityTransform& T, double minCos) {
  const MatrixX3d X = T.apply(side.sourceV);
  const std::vector<ClosestPoint> closest = TriangleTree(X, side.sourceF).closest(side.target);
  const MatrixX3d N = side.targetNormals ? detail::faceNormals(X, side.sourceF) : MatrixX3d();
  std::vector<double> d(closest.size());
  double sum = 0;
  for (std::size_t r = 0; r < closest.size(); ++r) sum += d[r] = std::sqrt(closest[r].squaredDistance);
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + Eigen::Index(sorted.size() / 2), sorted.end());
  const double limit = 3 * sorted[sorted.size() / 2] + 1e-9;
  std::vector<Eigen::Index> kept;
  for (std::size_t r = 0; r < closest.size(); ++r)
    if (d[r] <= limit &&
        (!side.targetNormals || side.targetNormals->row(Eigen::Index(r)).dot(N.row(closest[r].face)) >= minCos))
      kept.push_back(Eigen::Index(r));
  SidePairs p{MatrixX3d(kept.size(), 3), MatrixX3d(kept.size(), 3), sum / double(closest.size())};
  for (std::size_t k = 0; k < kept.size(); ++k) {
    const ClosestPoint& c = closest[std::size_t(kept[k])];
    Eigen::RowVector3d rest = Eigen::RowVector3d::Zero();
    for (int corner = 0; corner < 3; ++corner) rest += c.barycentric[corner] * side.sourceV.row(side.sourceF(c.face, corner));
    p.from.row(Eigen::Index(k)) = rest;
    p.to.row(Eigen::Index(k)) = side.target.row(kept[k]);
  }
  return p;
}

// Step 1 from one start: similarity ICP of the source towards the target's skin vertices (sides[0]) and,
// if given, its bones (sides[1]); each side weighs as much in the fit as the other. At most `iterations`,
// fewer once an iteration moves no matched source point by more than toleranceMm.
Alignment icpFrom(const SimilarityTransform& start, const std::vector<AlignedSide>& sides,
                  const PartialSkinRegistrationOptions& options, int iterations, double toleranceMm) {
  const double minCos = std::cos(options.registration.maxNormalAngleDeg * kPi / 180) - 1e-12;
  Alignment a;
  a.transform = start;
  for (int it = 0; it < iterations; ++it) {
    std::vector<SidePairs> pairs;
    Eigen::Index rows = 0;
    for (const AlignedSide& side : sides) {
      pairs.push_back(sidePairs(side, a.transform, minCos));
      rows += pairs.back().from.rows();
    }
    if (pairs[0].from.rows() < 3) break;
    MatrixX3d from(rows, 3), to(rows, 3);
    Eigen::VectorXd w(rows);
    Eigen::Index r = 0;
    for (const SidePairs& p : pairs) {
      from.middleRows(r, p.from.rows()) = p.from;
      to.middleRows(r, p.to.rows()) = p.to;
      w.segment(r, p.from.rows()).setConstant(1.0 / double(std::max<Eigen::Index>(p.from.rows(), 1)));
      r += p.from.rows();
    }
    const SimilarityTransform previous = a.transform;
    a.transform = fitSimilarity(from, to, w, true);
    a.matchedCentroid = pairs[0].from.colwise().mean().transpose();
    if ((a.transform.apply(pairs[0].from) - previous.apply(pairs[0].from)).rowwise().norm().maxCoeff() < toleranceMm)
      break;
  }
  a.score = 0;
  for (std::size_t k = 0; k < sides.size(); ++k) {
    const double mean = sidePairs(sides[k], a.transform, minCos).meanDistance;
    if (k == 0) a.meanDistance = mean;
    a.score += mean;
  }
  return a;
}

// At most `count` of the side's rows, evenly spread over them.
SkinSide everyNth(const SkinSide& side, int count) {
  const Eigen::Index step = (side.V.rows() + count - 1) / count;
  if (step <= 1) return side;
  std::vector<Eigen::Index> rows;
  for (Eigen::Index r = 0; r < side.V.rows(); r += step) rows.push_back(r);
  return {side.V(rows, Eigen::all), side.normals.rows() ? MatrixX3d(side.normals(rows, Eigen::all)) : MatrixX3d()};
}

// Step 1: the best of the starts along S. Every start runs alignIterations; the refinedStarts best of them
// then run on until they settle, and the best settled one wins. Two starts short of settling can score a
// few per cent apart in either order, as rounding falls, though both are on their way to the same place.
Alignment alignAlongBodyAxis(const MatrixX3d& Vs, const MatrixX3i& Fs, const SkinSide& skin,
                             const AlignmentBones* bones, const PartialSkinRegistrationOptions& options) {
  const SkinSide skinPoints = everyNth(skin, options.alignmentPoints);
  const SkinSide bonePoints = bones ? everyNth({bones->target, MatrixX3d()}, options.alignmentPoints) : SkinSide{};
  std::vector<AlignedSide> sides{{Vs, Fs, skinPoints.V, &skinPoints.normals}};
  if (bones) sides.push_back({bones->sourceV, bones->sourceF, bonePoints.V, nullptr});
  const double sourceFoot = Vs.col(2).minCoeff(), sourceHeight = Vs.col(2).maxCoeff() - sourceFoot;
  const double targetLow = skin.V.col(2).minCoeff(), targetHigh = skin.V.col(2).maxCoeff();
  const Eigen::RowVector3d targetCentroid = skin.V.colwise().mean();
  const double targetMiddle = (targetLow + targetHigh) / 2, halfSlab = (targetHigh - targetLow) / 2;
  std::vector<Alignment> screened;
  for (int k = 0; k < options.alignmentStarts; ++k) {
    const double f = options.alignmentStarts == 1
                         ? (options.startsFrom + options.startsTo) / 2
                         : options.startsFrom + (options.startsTo - options.startsFrom) * k / (options.alignmentStarts - 1);
    const double height = sourceFoot + f * sourceHeight;
    Eigen::RowVector3d slab = Eigen::RowVector3d::Zero();
    int count = 0;
    for (Eigen::Index v = 0; v < Vs.rows(); ++v)
      if (std::abs(Vs(v, 2) - height) <= halfSlab) {
        slab += Vs.row(v);
        ++count;
      }
    if (count == 0) continue;
    slab /= count;
    SimilarityTransform start;
    start.translation = Eigen::Vector3d(targetCentroid.x() - slab.x(), targetCentroid.y() - slab.y(), targetMiddle - height);
    screened.push_back(icpFrom(start, sides, options, options.alignIterations, 0));
  }
  std::sort(screened.begin(), screened.end(), [](const Alignment& a, const Alignment& b) { return a.score < b.score; });
  if (screened.empty() || !std::isfinite(screened.front().score))
    throw BadInput("", "partial skin registration: the source skin has no vertex at the heights tried");
  Alignment best;
  for (std::size_t k = 0; k < std::min(screened.size(), std::size_t(options.refinedStarts)); ++k) {
    const Alignment a = icpFrom(screened[k].transform, sides, options, options.refineIterations, options.settledMm);
    if (a.score < best.score) best = a;
  }
  return best;
}

}  // namespace

PartialSkinRegistration registerSkinToPartialTarget(const MatrixX3d& Vs, const MatrixX3i& Fs, const MatrixX3d& Vt,
                                                    const MatrixX3i& Ft, const std::vector<int>& targetCutVertices,
                                                    const PartialSkinRegistrationOptions& options,
                                                    const AlignmentBones* bones) {
  checkOptions(options);
  checkMesh(Vs, Fs, "source skin");
  checkMesh(Vt, Ft, "target skin");
  for (const int v : targetCutVertices)
    if (v < 0 || v >= Vt.rows())
      throw BadInput("", "partial skin registration: cut vertex " + std::to_string(v) + " is not a target vertex");
  const detail::Target target = detail::makePartialTarget(Vt, Ft, targetCutVertices, options.reciprocalToleranceMm);
  const SkinSide skin = targetSkinSide(target);

  PartialSkinRegistration result;
  if (bones) {
    checkMesh(bones->sourceV, bones->sourceF, "source bones");
    if (bones->target.rows() == 0 || !bones->target.allFinite())
      throw BadInput("", "partial skin registration: the target's bone points are empty or not finite");
  }
  const Alignment aligned = alignAlongBodyAxis(Vs, Fs, skin, bones, options);
  // The pose of the best start about the matched part of the source; its scale (the trunk's girth) only
  // with options.scaleSource, else the deformation fits the girth and the continuation fades it out.
  const SimilarityTransform& t = aligned.transform;
  result.girthScale = t.scale;
  result.alignmentLinear = options.scaleSource ? Eigen::Matrix3d(t.scale * t.rotation) : t.rotation;
  result.alignmentTranslation = t.scale * t.rotation * aligned.matchedCentroid + t.translation -
                                result.alignmentLinear * aligned.matchedCentroid;
  result.alignmentMeanDistance = aligned.meanDistance;
  const MatrixX3d Q = (Vs * result.alignmentLinear.transpose()).rowwise() + result.alignmentTranslation.transpose();

  std::vector<double> meanDistance;
  std::vector<char> reached;
  const MatrixX3d X = detail::deformOntoTarget(Q, Fs, target, {}, options.registration, meanDistance, reached);
  std::vector<Eigen::Index> pulledRows;
  for (Eigen::Index v = 0; v < X.rows(); ++v)
    if (reached[std::size_t(v)]) pulledRows.push_back(v);
  if (pulledRows.size() < 3)
    throw BadInput("", "partial skin registration: the target's skin pulls fewer than 3 source vertices");
  result.pulled = reached;

  result.continuation =
      fitSimilarity(MatrixX3d(Q(pulledRows, Eigen::all)), MatrixX3d(X(pulledRows, Eigen::all)), Eigen::VectorXd(), false);
  const MatrixX3d moved = result.continuation.apply(Q);
  MatrixX3d residual = MatrixX3d::Zero(X.rows(), 3);
  for (const Eigen::Index v : pulledRows) residual.row(v) = X.row(v) - moved.row(v);
  result.V = moved + MatrixX3d(extendHarmonically(residual, reached, Fs));

  std::tie(result.skinMeanDistance, result.skinMaxDistance) = detail::distances(TriangleTree(result.V, Fs).closest(skin.V));
  return result;
}

}  // namespace vesalius::transfer
