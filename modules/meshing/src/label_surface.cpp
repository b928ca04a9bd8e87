// The surface of one label (label_surface.h): flying edges, world mapping, smoothing, decimation.
#include "polydata_convert.h"
#include "vesalius/core/error.h"
#include "vesalius/core/mesh_measures.h"
#include "vesalius/meshing/label_surface.h"
#include "vesalius/core/mesh_measures.h"

#include <vtkDiscreteFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkPoints.h>
#include <vtkQuadricDecimation.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <optional>
#include <string>

namespace vesalius::meshing {
namespace {

struct IndexBox {
  Eigen::Vector3i lo, hi;  // inclusive voxel index bounds
};

std::optional<IndexBox> labelBounds(const Grid<Label>& labels, Label id) {
  const Eigen::Vector3i& s = labels.geometry.size;
  IndexBox box{s, Eigen::Vector3i::Constant(-1)};
  for (int k = 0; k < s.z(); ++k)
    for (int j = 0; j < s.y(); ++j)
      for (int i = 0; i < s.x(); ++i)
        if (labels.at(i, j, k) == id) {
          box.lo = box.lo.cwiseMin(Eigen::Vector3i(i, j, k));
          box.hi = box.hi.cwiseMax(Eigen::Vector3i(i, j, k));
        }
  if (box.hi.x() < 0) return std::nullopt;
  return box;
}

// 1 where the label is, 0 elsewhere, over the box grown by one voxel on every side; image index
// (0, 0, 0) is grid voxel box.lo - 1. Unit spacing, zero origin: world mapping is done afterwards.
vtkSmartPointer<vtkImageData> paddedMask(const Grid<Label>& labels, Label id, const IndexBox& box) {
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

vtkSmartPointer<vtkPolyData> decimate(vtkPolyData* surface, int targetFaces) {
  const vtkIdType faces = surface->GetNumberOfPolys();
  if (targetFaces <= 0 || faces <= targetFaces) return surface;
  auto quadric = vtkSmartPointer<vtkQuadricDecimation>::New();
  quadric->SetInputData(surface);
  quadric->SetTargetReduction(1.0 - double(targetFaces) / double(faces));
  quadric->VolumePreservationOn();
  quadric->Update();
  return quadric->GetOutput();
}

void validate(const SurfaceOptions& o) {
  if (o.smoothingIterations < 0 || !(o.passBand > 0.0 && o.passBand < 2.0) || o.targetFaces < 0)
    throw UsageError("surface options need smoothing iterations >= 0, 0 < pass band < 2, target faces >= 0");
}

}  // namespace

TriMesh labelSurface(const LabelMap& labels, Label id, const SurfaceOptions& options) {
  validate(options);
  const std::optional<IndexBox> box = labelBounds(labels.labels, id);
  if (!box) throw BadInput("", "label " + std::to_string(id) + " has no voxels");
  const GridGeometry& geometry = labels.labels.geometry;
  auto surface = contour(paddedMask(labels.labels, id, *box), geometry, box->lo - Eigen::Vector3i::Ones());
  TriMesh mesh = detail::toTriMesh(decimate(smooth(surface, options), options.targetFaces));
  // Flying edges orients every triangle consistently; a direction matrix with negative determinant
  // (RAS-stored scans read as LPS) turns the whole surface inside out, which the sign of the volume shows.
  if (enclosedVolume(mesh.V, mesh.F) < 0.0) mesh.F.col(1).swap(mesh.F.col(2));
  mesh.faceAttributes.integer[kLabel] = Eigen::VectorXi::Constant(mesh.F.rows(), int(id));
  return mesh;
}

}  // namespace vesalius::meshing
