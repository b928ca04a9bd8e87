#include "vesalius/patient/bone_onto_label.h"

#include "vesalius/core/error.h"
#include "vesalius/core/triangle_tree.h"
#include "vesalius/fit/affine_icp.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/meshing/midpoint_subdivision.h"
#include "vesalius/meshing/surface_samples.h"
#include "vesalius/transfer/surface_harmonic_extension.h"

#include <algorithm>
#include <cmath>

namespace vesalius::patient {

namespace {

// How far p lies outside the box of the scan's voxel centres, mm (0 inside it, as meshing::withinScan
// decides inside).
double outsideScan(const GridGeometry& g, const Eigen::Vector3d& p) {
  const Eigen::Vector3d index = (g.direction.transpose() * (p - g.origin)).cwiseQuotient(g.spacing);
  Eigen::Vector3d beyond = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const double past = std::max(-index[k], index[k] - double(g.size[k] - 1));
    if (past > 1e-9) beyond[k] = past * g.spacing[k];
  }
  return beyond.norm();
}

std::vector<std::vector<int>> vertexNeighbours(const MatrixX3i& F, Eigen::Index vertices) {
  std::vector<std::vector<int>> n(static_cast<std::size_t>(vertices));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      n[std::size_t(F(f, k))].push_back(F(f, (k + 1) % 3));
      n[std::size_t(F(f, (k + 1) % 3))].push_back(F(f, k));
    }
  for (std::vector<int>& list : n) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return n;
}

// Jacobi passes of the uniform Laplacian: each row half itself, half its neighbours' mean.
void smooth(Eigen::MatrixXd& values, const std::vector<std::vector<int>>& neighbours, int passes) {
  Eigen::MatrixXd next(values.rows(), values.cols());
  for (int pass = 0; pass < passes; ++pass) {
    for (Eigen::Index v = 0; v < values.rows(); ++v) {
      const std::vector<int>& n = neighbours[std::size_t(v)];
      if (n.empty()) {
        next.row(v) = values.row(v);
        continue;
      }
      Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(values.cols());
      for (const int u : n) mean += values.row(u);
      next.row(v) = 0.5 * values.row(v) + 0.5 * mean / double(n.size());
    }
    values.swap(next);
  }
}

// The vertices that the faces of `mesh` use.
MatrixX3d usedVertices(const TriMesh& mesh) {
  std::vector<char> used(std::size_t(mesh.V.rows()), 0);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) used[std::size_t(mesh.F(f, k))] = 1;
  MatrixX3d out(std::count(used.begin(), used.end(), 1), 3);
  Eigen::Index row = 0;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (used[std::size_t(v)]) out.row(row++) = mesh.V.row(v);
  return out;
}

}  // namespace

BoneOntoLabel registerBoneOntoLabel(const TriMesh& bone, const LabelMap& labels, const std::vector<Label>& ids,
                                    const BoneOntoLabelOptions& options, const std::string& boneSource,
                                    const std::string& labelsSource) {
  if (bone.F.rows() == 0) throw BadInput(boneSource, "the bone mesh has no triangles");
  const GridGeometry& scan = labels.labels.geometry;
  TriMesh target;
  for (const meshing::LabelSurface& s : meshing::labelSurfaces(labels, ids)) {
    const TriMesh inside = meshing::withinScan(s.mesh, scan);
    target = target.F.rows() ? concatenate(target, inside) : inside;
  }
  if (target.F.rows() == 0)
    throw BadInput(labelsSource, "the bone's label has no boundary inside the scan to register " + boneSource + " to");
  const MatrixX3d targetPoints = usedVertices(target);
  const TriangleTree targetTree(target.V, target.F);

  BoneOntoLabel out;
  TriMesh mesh = meshing::subdivideMidpoints(bone, meshing::midpointLevelsFor(bone, options.maxEdgeMm));
  const int spread = std::min<int>(options.affineTargets, int(target.F.rows()));
  if (spread > 0) mesh = fit::refineAffineIcp(std::move(mesh), meshing::spreadSurfacePoints(target, spread, 1));

  const Eigen::Index n = mesh.V.rows();
  const std::vector<std::vector<int>> neighbours = vertexNeighbours(mesh.F, n);
  for (int round = 0; round < options.rounds; ++round) {
    Eigen::MatrixXd pull = Eigen::MatrixXd::Zero(n, 3);
    Eigen::VectorXd weight = Eigen::VectorXd::Zero(n);
    // Vertex to boundary, inside the field of view.
    Eigen::VectorXd beyond(n);
    for (Eigen::Index v = 0; v < n; ++v) beyond[v] = outsideScan(scan, mesh.V.row(v).transpose());
    const std::vector<ClosestPoint> forward = targetTree.closest(mesh.V);
    for (Eigen::Index v = 0; v < n; ++v) {
      const ClosestPoint& c = forward[std::size_t(v)];
      if (beyond[v] > 0) continue;
      pull.row(v) += (c.point - mesh.V.row(v).transpose()).transpose();
      weight[v] += 1;
    }
    // Boundary to mesh: each boundary point pulls the triangle closest to it, shared by its corners.
    const TriangleTree meshTree(mesh.V, mesh.F);
    const std::vector<ClosestPoint> backward = meshTree.closest(targetPoints);
    for (Eigen::Index p = 0; p < targetPoints.rows(); ++p) {
      const ClosestPoint& c = backward[std::size_t(p)];
      const Eigen::RowVector3d move = targetPoints.row(p) - c.point.transpose();
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.F(c.face, k);
        pull.row(v) += c.barycentric[k] * move;
        weight[v] += c.barycentric[k];
      }
    }
    std::vector<char> known(std::size_t(n), 0);
    bool pulled = false;
    for (Eigen::Index v = 0; v < n; ++v)
      if (weight[v] > 1e-9) {
        pull.row(v) /= weight[v];
        known[std::size_t(v)] = 1;
        pulled = true;
      } else if (beyond[v] > options.fadeMm) {
        known[std::size_t(v)] = 1;  // its pull stays 0
      }
    if (!pulled) break;
    Eigen::MatrixXd move = transfer::extendHarmonically(pull, known, mesh.F);
    smooth(move, neighbours, options.smoothing >> round);
    mesh.V += move;
  }

  for (Eigen::Index v = 0; v < n; ++v) out.verticesInFieldOfView += outsideScan(scan, mesh.V.row(v).transpose()) == 0;
  const std::vector<ClosestPoint> distances = TriangleTree(mesh.V, mesh.F).closest(targetPoints);
  for (const ClosestPoint& c : distances) {
    const double d = std::sqrt(c.squaredDistance);
    out.boundaryToMeshMeanMm += d / double(distances.size());
    out.boundaryToMeshMaxMm = std::max(out.boundaryToMeshMaxMm, d);
  }
  out.mesh = std::move(mesh);
  return out;
}

}  // namespace vesalius::patient
