// Posed scans and label maps (posed_volume.h).
#include "vesalius/posing/posed_volume.h"

#include "vesalius/core/error.h"
#include "vesalius/core/grid_sampling.h"

#include <tbb/parallel_for.h>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace vesalius::posing {
namespace {

using Eigen::Index;
using Corners = Eigen::Matrix<double, 3, 4>;

constexpr int kSlab = 4;  // z-planes per task: enough work per task, few tets visited by two tasks
// A centre on a face shared by two tets must be inside one of them despite rounding; a fold decides the
// winner by tet index anyway, so a small overlap costs nothing.
constexpr double kInside = 1e-10;

void checkInputs(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, const GridGeometry& in,
                 std::size_t valueCount, const GridGeometry& out, const RigidParts* rigid) {
  if (posedV.rows() != restV.rows())
    throw BadInput("", "posed volume: " + std::to_string(posedV.rows()) + " posed vertices for " +
                           std::to_string(restV.rows()) + " rest vertices");
  if (T.size() > 0 && (T.minCoeff() < 0 || T.maxCoeff() >= restV.rows()))
    throw BadInput("", "posed volume: a tet refers to a vertex that does not exist");
  in.validate("posed volume input");
  out.validate("posed volume output");
  if (std::int64_t(valueCount) != in.voxelCount())
    throw BadInput("", "posed volume: " + std::to_string(valueCount) + " values for " +
                           std::to_string(in.voxelCount()) + " voxels");
  if (!rigid || rigid->restFromPosed.empty()) return;
  if (rigid->parts.geometry.size != out.size || std::int64_t(rigid->parts.values.size()) != out.voxelCount())
    throw BadInput("", "posed volume: the rigid parts are not on the output grid");
  const auto highest = std::max_element(rigid->parts.values.begin(), rigid->parts.values.end());
  if (highest != rigid->parts.values.end() && std::size_t(*highest) > rigid->restFromPosed.size())
    throw BadInput("", "posed volume: rigid part " + std::to_string(*highest) + " of " +
                           std::to_string(rigid->restFromPosed.size()) + " has no map");
}

// World point → continuous voxel index, as one affine map.
Eigen::Affine3d worldToIndexMap(const GridGeometry& g) { return Eigen::Affine3d(g.indexToWorldMatrix()).inverse(); }

// Corners of tet t (columns) in the continuous index space of `toIndex`.
Corners corners(const MatrixX3d& V, const MatrixX4i& T, Index t, const Eigen::Affine3d& toIndex) {
  Corners c;
  for (int a = 0; a < 4; ++a) c.col(a) = toIndex * V.row(T(t, a)).transpose();
  return c;
}

// Inclusive index range of the voxel centres in the bounding box of `c`, clipped to the grid (lo > hi
// on some axis when it misses the grid).
struct IndexBox {
  Eigen::Vector3i lo, hi;
};
IndexBox indexBox(const Corners& c, const Eigen::Vector3i& size) {
  IndexBox b;
  for (int d = 0; d < 3; ++d) {
    b.lo[d] = int(std::max(0.0, std::ceil(c.row(d).minCoeff() - kInside)));
    b.hi[d] = int(std::min(double(size[d] - 1), std::floor(c.row(d).maxCoeff() + kInside)));
  }
  return b;
}

// For each z-slab of the output, the tets whose bounding box reaches it, in increasing index order.
std::vector<std::vector<int>> tetsBySlab(const MatrixX3d& posedV, const MatrixX4i& T, const GridGeometry& out,
                                         const Eigen::Affine3d& outIndex) {
  std::vector<IndexBox> boxes(std::size_t(T.rows()));
  tbb::parallel_for(Index(0), T.rows(), [&](Index t) { boxes[std::size_t(t)] = indexBox(corners(posedV, T, t, outIndex), out.size); });
  std::vector<std::vector<int>> slabs(std::size_t((out.size.z() + kSlab - 1) / kSlab));
  for (Index t = 0; t < T.rows(); ++t) {
    const IndexBox& b = boxes[std::size_t(t)];
    if ((b.lo.array() > b.hi.array()).any()) continue;
    for (int s = b.lo.z() / kSlab; s <= b.hi.z() / kSlab; ++s) slabs[std::size_t(s)].push_back(int(t));
  }
  return slabs;
}

// Writes the voxels of posed tet t with z index in [kFrom, kTo] that no lower tet has covered.
template <class Value, class Sample>
void fillTet(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, Index t,
             const Eigen::Affine3d& outIndex, const Eigen::Affine3d& inIndex, int kFrom, int kTo,
             Grid<Value>& posed, std::vector<char>& covered, const Sample& sample) {
  const Corners q = corners(posedV, T, t, outIndex);
  const Eigen::Matrix3d E = q.rightCols<3>().colwise() - q.col(0);
  const double det = E.determinant();
  // A collapsed posed tet covers no voxel centre but its neighbours' (and E⁻¹ would be meaningless).
  if (!(std::abs(det) > 1e-12 * E.colwise().norm().prod())) return;
  const Eigen::Matrix3d toBarycentric = E.inverse();
  const Corners r = corners(restV, T, t, inIndex);
  const Eigen::Matrix3d restEdges = r.rightCols<3>().colwise() - r.col(0);
  IndexBox b = indexBox(q, posed.geometry.size);
  b.lo.z() = std::max(b.lo.z(), kFrom);
  b.hi.z() = std::min(b.hi.z(), kTo);
  for (int k = b.lo.z(); k <= b.hi.z(); ++k)
    for (int j = b.lo.y(); j <= b.hi.y(); ++j)
      for (int i = b.lo.x(); i <= b.hi.x(); ++i) {
        const Eigen::Vector3d lambda = toBarycentric * (Eigen::Vector3d(i, j, k) - q.col(0));
        if (lambda.minCoeff() < -kInside || lambda.sum() > 1 + kInside) continue;
        const std::int64_t v = posed.geometry.linearIndex(i, j, k);
        if (covered[std::size_t(v)]) continue;
        covered[std::size_t(v)] = 1;
        posed.values[std::size_t(v)] = sample(Eigen::Vector3d(r.col(0) + restEdges * lambda));
      }
}

// The rasterizer shared by scans and labels. sample(index) gives the input's value at a continuous index
// of the input grid (or the background outside it).
// Writes the voxels of the rigid parts with z index in [kFrom, kTo].
template <class Value, class Sample>
void fillRigid(const RigidParts& rigid, const Eigen::Affine3d& inIndex, int kFrom, int kTo, Grid<Value>& posed,
               std::vector<char>& covered, const Sample& sample) {
  const GridGeometry& out = posed.geometry;
  const Eigen::Affine3d outWorld(out.indexToWorldMatrix());
  for (int k = kFrom; k <= kTo; ++k)
    for (int j = 0; j < out.size.y(); ++j)
      for (int i = 0; i < out.size.x(); ++i) {
        const std::int64_t v = out.linearIndex(i, j, k);
        const Label p = rigid.parts.values[std::size_t(v)];
        if (p == 0) continue;
        covered[std::size_t(v)] = 1;
        posed.values[std::size_t(v)] = sample(Eigen::Vector3d(inIndex * (rigid.restFromPosed[p - 1] * (outWorld * Eigen::Vector3d(i, j, k)))));
      }
}

template <class Value, class Sample>
Grid<Value> rasterize(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, const GridGeometry& in,
                      const GridGeometry& out, const RigidParts* rigid, Value background, const Sample& sample) {
  const Eigen::Affine3d outIndex = worldToIndexMap(out), inIndex = worldToIndexMap(in);
  const std::vector<std::vector<int>> slabs = tetsBySlab(posedV, T, out, outIndex);
  Grid<Value> posed(out, background);
  std::vector<char> covered(std::size_t(out.voxelCount()), 0);
  // Each task owns the voxels of one slab, so no two tasks write the same voxel or flag.
  tbb::parallel_for(std::size_t(0), slabs.size(), [&](std::size_t s) {
    const int kFrom = int(s) * kSlab, kTo = std::min(kFrom + kSlab, out.size.z()) - 1;
    if (rigid && !rigid->restFromPosed.empty()) fillRigid(*rigid, inIndex, kFrom, kTo, posed, covered, sample);
    for (const int t : slabs[s]) fillTet(restV, T, posedV, t, outIndex, inIndex, kFrom, kTo, posed, covered, sample);
  });
  return posed;
}

}  // namespace

Image poseImage(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, const Image& scan,
                const PosedVolumeOptions& options) {
  const GridGeometry& out = options.outputGeometry ? *options.outputGeometry : scan.geometry;
  checkInputs(restV, T, posedV, scan.geometry, scan.values.size(), out, options.rigid);
  const double background =
      options.background ? *options.background : double(*std::min_element(scan.values.begin(), scan.values.end()));
  if (!std::isfinite(background)) throw BadInput("", "posed volume: the background is not finite");
  const float fill = float(background);
  Image posed;
  static_cast<Grid<float>&>(posed) =
      rasterize(restV, T, posedV, scan.geometry, out, options.rigid, fill, [&](const Eigen::Vector3d& c) {
        return insideVoxels(c, scan.geometry.size) ? float(sampleTrilinear(scan, c)) : fill;
      });
  posed.fileType = scan.fileType;
  return posed;
}

LabelMap poseLabels(const MatrixX3d& restV, const MatrixX4i& T, const MatrixX3d& posedV, const LabelMap& labels,
                    const PosedVolumeOptions& options) {
  const Grid<Label>& in = labels.labels;
  const GridGeometry& out = options.outputGeometry ? *options.outputGeometry : in.geometry;
  checkInputs(restV, T, posedV, in.geometry, in.values.size(), out, options.rigid);
  const double background = options.background.value_or(0.0);
  if (!(background >= 0 && background <= std::numeric_limits<Label>::max() && background == std::floor(background)))
    throw BadInput("", "posed volume: background " + std::to_string(background) + " is not a label");
  const Label fill = Label(background);
  LabelMap posed;
  posed.table = labels.table;
  posed.labels = rasterize(restV, T, posedV, in.geometry, out, options.rigid, fill, [&](const Eigen::Vector3d& c) {
    if (!insideVoxels(c, in.geometry.size)) return fill;
    // The far half voxel rounds up to `size`, which belongs to the last voxel.
    const Eigen::Vector3i n = (c.array() + 0.5).floor().cast<int>().min(in.geometry.size.array() - 1);
    return in.at(n.x(), n.y(), n.z());
  });
  return posed;
}

}  // namespace vesalius::posing
