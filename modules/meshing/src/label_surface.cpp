// The surface of one label (label_surface.h): flying edges, world mapping, smoothing, decimation.
#include "vesalius/meshing/label_surface.h"

#include "label_surface_in_box.h"
#include "restore_volume.h"
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/core/self_intersections.h"
#include "vesalius/io/polydata.h"
#include "vesalius/meshing/decimate_surface.h"

#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkPoints.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <algorithm>
#include <string>

namespace vesalius::meshing {
namespace {

// 1 where the label is, 0 elsewhere, over the box grown by one voxel on every side; image index
// (0, 0, 0) is grid voxel box.lo - 1. Unit spacing, zero origin: world mapping is done afterwards.
vtkSmartPointer<vtkImageData> paddedMask(const Grid<Label>& labels, Label id, const LabelBox& box) {
  const Eigen::Vector3i dims = box.hi - box.lo + Eigen::Vector3i::Constant(3);
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(dims.x(), dims.y(), dims.z());
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* out = static_cast<unsigned char*>(image->GetScalarPointer());
  std::fill(out, out + std::size_t(dims.prod()), 0);
  for (int k = box.lo.z(); k <= box.hi.z(); ++k)
    for (int j = box.lo.y(); j <= box.hi.y(); ++j)
      for (int i = box.lo.x(); i <= box.hi.x(); ++i) {
        const Eigen::Vector3i p = Eigen::Vector3i(i, j, k) - box.lo + Eigen::Vector3i::Ones();
        out[p.x() + std::size_t(dims.x()) * (p.y() + std::size_t(dims.y()) * p.z())] =
            labels.at(i, j, k) == id;
      }
  return image;
}

vtkSmartPointer<vtkPolyData> contour(vtkImageData* mask, const GridGeometry& geometry,
                                     const Eigen::Vector3i& offset) {
  auto flyingEdges = vtkSmartPointer<vtkDiscreteFlyingEdges3D>::New();
  flyingEdges->SetInputData(mask);
  flyingEdges->SetValue(0, 1.0);
  flyingEdges->ComputeNormalsOff();
  flyingEdges->ComputeGradientsOff();
  flyingEdges->ComputeScalarsOff();
  flyingEdges->Update();
  vtkSmartPointer<vtkPolyData> surface = flyingEdges->GetOutput();
  vtkPoints* points = surface->GetPoints();
  for (vtkIdType p = 0; p < points->GetNumberOfPoints(); ++p) {
    double x[3];
    points->GetPoint(p, x);
    const Eigen::Vector3d world =
        geometry.indexToWorld(Eigen::Vector3d(x[0], x[1], x[2]) + offset.cast<double>());
    points->SetPoint(p, world.data());
  }
  return surface;
}

vtkSmartPointer<vtkPolyData> smooth(vtkPolyData* surface, const SurfaceOptions& options) {
  if (options.smoothingIterations == 0) return surface;
  auto sinc = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
  sinc->SetInputData(surface);
  sinc->SetNumberOfIterations(options.smoothingIterations);
  sinc->SetPassBand(options.passBand);
  sinc->NormalizeCoordinatesOn();
  sinc->FeatureEdgeSmoothingOff();
  sinc->BoundarySmoothingOff();
  sinc->NonManifoldSmoothingOn();
  sinc->Update();
  return sinc->GetOutput();
}

void validate(const SurfaceOptions& o) {
  // One windowed-sinc iteration is a degree-one filter that VTK cannot fit ("an optimal offset could not be
  // found") and returns a collapsed surface.
  if (o.smoothingIterations < 0 || o.smoothingIterations == 1 || !(o.passBand > 0.0 && o.passBand < 2.0) ||
      o.targetFaces < 0)
    throw UsageError(
        "surface options need smoothing iterations 0 or >= 2, 0 < pass band < 2, target faces >= 0");
}

// Smoothing, decimation and outward orientation of one contour.
TriMesh smoothedSurface(vtkPolyData* surface, const SurfaceOptions& options) {
  TriMesh mesh = decimateSurface(io::fromPolyData(smooth(surface, options), "label surface"), options.targetFaces);
  // Flying edges orients every triangle consistently; a direction matrix with negative determinant
  // (a mirrored grid) turns the whole surface inside out, which the sign of the volume shows.
  if (enclosedVolume(mesh.V, mesh.F) < 0.0) mesh.F.col(1).swap(mesh.F.col(2));
  return mesh;
}

bool crosses(const TriMesh& mesh) { return !selfIntersections(mesh.V, mesh.F).empty(); }

// Where the volume offset pushed a thin flap or two close pieces through each other, the vertices of the
// crossing triangles and their neighbours go back to `before` (a clean surface); up to eight rounds (the
// demo's body needs seven). Only triangles that moved in a round can cross afterwards, so later rounds
// test only those. Returns whether the surface is then clean. The rest of the surface keeps its offset.
bool offsetOnlyWhereClean(TriMesh& offset, const MatrixX3d& before) {
  std::vector<std::pair<int, int>> pairs = selfIntersections(offset.V, offset.F);
  for (int round = 0; round < 8 && !pairs.empty(); ++round) {
    std::vector<bool> crossing(std::size_t(offset.V.rows()), false), back = crossing;
    for (const auto& [f, g] : pairs)
      for (int k = 0; k < 3; ++k) crossing[std::size_t(offset.F(f, k))] = crossing[std::size_t(offset.F(g, k))] = true;
    std::vector<int> moved;
    for (Eigen::Index f = 0; f < offset.F.rows(); ++f)
      if (crossing[std::size_t(offset.F(f, 0))] || crossing[std::size_t(offset.F(f, 1))] ||
          crossing[std::size_t(offset.F(f, 2))])
        for (int k = 0; k < 3; ++k) back[std::size_t(offset.F(f, k))] = true;
    for (Eigen::Index v = 0; v < offset.V.rows(); ++v)
      if (back[std::size_t(v)]) offset.V.row(v) = before.row(v);
    for (Eigen::Index f = 0; f < offset.F.rows(); ++f)
      if (back[std::size_t(offset.F(f, 0))] || back[std::size_t(offset.F(f, 1))] || back[std::size_t(offset.F(f, 2))])
        moved.push_back(int(f));
    pairs = selfIntersections(offset.V, offset.F, moved);
  }
  return pairs.empty();
}

// Halving the smoothing, skipping the one iteration VTK cannot do: 20, 10, 5, 2, 0.
int lessSmoothing(int iterations) { return iterations / 2 == 1 ? 0 : iterations / 2; }

}  // namespace

TriMesh detail::labelSurfaceInBox(const LabelMap& labels, Label id, const LabelBox& box,
                                  const SurfaceOptions& options) {
  validate(options);
  const GridGeometry& geometry = labels.labels.geometry;
  auto contoured = contour(paddedMask(labels.labels, id, box), geometry, box.lo - Eigen::Vector3i::Ones());
  const double voxelVolume = double(box.voxels) * geometry.spacing.prod();
  const double maxOffset = 0.5 * geometry.spacing.minCoeff();
  // Smoothing can pull the two sides of a thin part through each other (the test CT's left hip bone at
  // 20 iterations); TetGen refuses such surfaces. The smoothing is halved until the surface is clean; the
  // volume offset is then kept wherever it crosses nothing.
  SurfaceOptions attempt = options;
  TriMesh mesh;
  for (;;) {
    mesh = smoothedSurface(contoured, attempt);
    if (!options.avoidSelfIntersections) {
      if (options.preserveVolume) detail::restoreVolume(mesh, voxelVolume, maxOffset);
      break;
    }
    const bool clean = !crosses(mesh);
    if (clean || attempt.smoothingIterations == 0) {
      TriMesh offset = mesh;
      if (clean && options.preserveVolume && detail::restoreVolume(offset, voxelVolume, maxOffset) &&
          offsetOnlyWhereClean(offset, mesh.V))
        mesh = std::move(offset);
      break;
    }
    attempt.smoothingIterations = lessSmoothing(attempt.smoothingIterations);
  }
  mesh.faceAttributes.integer[kLabel] = Eigen::VectorXi::Constant(mesh.F.rows(), int(id));
  return mesh;
}

TriMesh labelSurface(const LabelMap& labels, Label id, const SurfaceOptions& options) {
  validate(options);
  const std::vector<LabelBox> boxes = labelBoxes(labels.labels);
  if (id == 0) throw UsageError("label 0 is the background and has no surface");
  if (id >= boxes.size() || boxes[id].voxels == 0)
    throw BadInput("", "label " + std::to_string(id) + " has no voxels");
  return detail::labelSurfaceInBox(labels, id, boxes[id], options);
}

}  // namespace vesalius::meshing
