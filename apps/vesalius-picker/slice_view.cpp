#include "slice_view.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCutter.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapToWindowLevelColors.h>
#include <vtkImageMapper3D.h>
#include <vtkImageReslice.h>
#include <vtkMatrix4x4.h>
#include <vtkPlane.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace vesalius::picker {
namespace {

// Heights above the image (toward the camera) of what is drawn over it, mm in plane coordinates.
constexpr double kLabelLayerHeight = 0.2, kContourHeight = 0.4, kCrosshairHeight = 0.6, kMarkerHeight = 1.0;
constexpr double kMarkerRadiusPixels = 6, kCameraDistance = 1000;
constexpr double kFitMargin = 1.05;  // the scan's voxel centres fill the view but for 5 %

vtkSmartPointer<vtkMatrix4x4> liftedInverse(vtkMatrix4x4* planeToWorld, double height) {
  auto worldToPlane = vtkSmartPointer<vtkMatrix4x4>::New();
  vtkMatrix4x4::Invert(planeToWorld, worldToPlane);
  worldToPlane->SetElement(2, 3, worldToPlane->GetElement(2, 3) + height);
  return worldToPlane;
}

// "S 12.5" for the axial slice through `world`, "P -3.0" for coronal, "L 40.2" for sagittal.
std::string slicePositionText(SliceAxis axis, const Eigen::Vector3d& world) {
  const int component = axis == SliceAxis::Axial ? 2 : axis == SliceAxis::Coronal ? 1 : 0;
  const char* letter = axis == SliceAxis::Axial ? "S" : axis == SliceAxis::Coronal ? "P" : "L";
  char text[64];
  std::snprintf(text, sizeof text, "%s %.1f mm", letter, world[component]);
  return text;
}

}  // namespace

SliceView::SliceView(SliceAxis axis, const ScanVolume& scan, vtkRenderWindow* window,
                     const std::array<double, 4>& viewport)
    : axis_(axis), frame_(SliceFrame::of(axis)), extent_(sliceExtent(scan.geometry(), frame_)), scan_(scan) {
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->SetViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
  window->AddRenderer(renderer_);

  const double pixel = scan.geometry().spacing.minCoeff();
  const Eigen::Vector2d low = extent_.centre.head<2>() - extent_.halfSize.head<2>();
  reslice_ = vtkSmartPointer<vtkImageReslice>::New();
  reslice_->SetInputData(scan.indexSpaceImage());
  reslice_->SetOutputDimensionality(2);
  reslice_->SetInterpolationModeToLinear();
  reslice_->SetBackgroundLevel(*std::min_element(scan.image().values.begin(), scan.image().values.end()));
  reslice_->SetOutputSpacing(pixel, pixel, 1);
  reslice_->SetOutputOrigin(low.x(), low.y(), 0);
  reslice_->SetOutputExtent(0, int(std::ceil(2 * extent_.halfSize.x() / pixel)), 0,
                            int(std::ceil(2 * extent_.halfSize.y() / pixel)), 0, 0);
  planeToWorld_ = vtkSmartPointer<vtkMatrix4x4>::New();
  resliceAxes_ = vtkSmartPointer<vtkMatrix4x4>::New();
  reslice_->SetResliceAxes(resliceAxes_);

  colours_ = vtkSmartPointer<vtkImageMapToWindowLevelColors>::New();
  colours_->SetInputConnection(reslice_->GetOutputPort());
  colours_->SetOutputFormatToRGB();
  image_ = vtkSmartPointer<vtkImageActor>::New();
  image_->GetMapper()->SetInputConnection(colours_->GetOutputPort());
  image_->InterpolateOff();
  renderer_->AddActor(image_);

  crosshair_ = vtkSmartPointer<vtkPolyData>::New();
  auto crosshairMapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  crosshairMapper->SetInputData(crosshair_);
  auto crosshairActor = vtkSmartPointer<vtkActor>::New();
  crosshairActor->SetMapper(crosshairMapper);
  // Opaque: one translucent actor makes VTK run its order-independent translucency pass at every render.
  crosshairActor->GetProperty()->SetColor(0.2, 0.9, 0.3);
  crosshairActor->GetProperty()->SetAmbient(1.0);
  crosshairActor->GetProperty()->SetDiffuse(0.0);
  renderer_->AddActor(crosshairActor);

  title_ = vtkSmartPointer<vtkTextActor>::New();
  title_->GetTextProperty()->SetFontSize(14);
  title_->GetTextProperty()->SetColor(1, 1, 1);
  title_->SetPosition(6, 6);
  renderer_->AddActor2D(title_);

  markers_ = std::make_unique<MarkerLayer>(renderer_, GlyphShape::Disc);
  renderer_->GetActiveCamera()->ParallelProjectionOn();
  cursor_ = extent_.centre.head<2>();
  depth_ = extent_.centre.z();
  updateSlicePlane();
}

SliceView::~SliceView() = default;

bool SliceView::contains(int displayX, int displayY) const {
  return renderer_->IsInViewport(displayX, displayY) != 0;
}

void SliceView::stepSlices(int steps) {
  const double lowest = extent_.centre.z() - extent_.halfSize.z();
  const double highest = extent_.centre.z() + extent_.halfSize.z();
  const double forwardSign = frame_.forward.dot(frame_.normal);
  depth_ = std::clamp(depth_ + steps * forwardSign * extent_.depthStep, lowest, highest);
  updateSlicePlane();
}

void SliceView::showSliceThrough(const Eigen::Vector3d& world) {
  const Eigen::Vector3d plane = frame_.toPlane(world);
  depth_ = plane.z();
  cursor_ = plane.head<2>();
  updateSlicePlane();
}

Eigen::Vector3d SliceView::displayToWorld(int displayX, int displayY) const {
  renderer_->SetDisplayPoint(displayX, displayY, 0);
  renderer_->DisplayToWorld();
  const double* point = renderer_->GetWorldPoint();
  return frame_.toWorld(Eigen::Vector3d(point[0] / point[3], point[1] / point[3], depth_));
}

double SliceView::millimetresPerPixel() const {
  const int* size = renderer_->GetSize();
  return 2 * renderer_->GetActiveCamera()->GetParallelScale() / std::max(size[1], 1);
}

bool SliceView::isOnSlice(const Eigen::Vector3d& world) const {
  return std::abs(frame_.toPlane(world).z() - depth_) <= extent_.depthStep / 2;
}

void SliceView::zoom(double factor) {
  changed_ = true;
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetParallelScale(camera->GetParallelScale() / factor);
}

void SliceView::pan(int dxPixels, int dyPixels) {
  changed_ = true;
  vtkCamera* camera = renderer_->GetActiveCamera();
  const double* focal = camera->GetFocalPoint();
  const double mm = millimetresPerPixel();
  const double x = focal[0] - dxPixels * mm, y = focal[1] - dyPixels * mm;
  camera->SetFocalPoint(x, y, 0);
  camera->SetPosition(x, y, kCameraDistance);
}

void SliceView::fitToScan() {
  changed_ = true;
  vtkCamera* camera = renderer_->GetActiveCamera();
  camera->SetFocalPoint(extent_.centre.x(), extent_.centre.y(), 0);
  camera->SetPosition(extent_.centre.x(), extent_.centre.y(), kCameraDistance);
  camera->SetViewUp(0, 1, 0);
  camera->SetClippingRange(kCameraDistance / 2, 2 * kCameraDistance);
  const int* size = renderer_->GetSize();
  const double aspect = double(std::max(size[0], 1)) / std::max(size[1], 1);
  camera->SetParallelScale(kFitMargin * std::max(extent_.halfSize.y(), extent_.halfSize.x() / aspect));
}

void SliceView::setWindowLevel(const WindowLevel& windowLevel) {
  changed_ = true;
  colours_->SetWindow(windowLevel.window);
  colours_->SetLevel(windowLevel.level);
}

void SliceView::showMarkers(const MarkerSet& markers, std::uint64_t revision) {
  const auto now = std::make_tuple(revision, depth_, millimetresPerPixel());
  if (drawnMarkers_ == now) return;
  drawnMarkers_ = now;
  changed_ = true;
  std::vector<MarkerGlyph> glyphs;
  for (const std::size_t i : markersOnSlice(markers, revision)) {
    const Marker& m = markers.markers[i];
    if (!hasPosition(m.status) || !m.visible) continue;
    Eigen::Vector3d plane = frame_.toPlane(m.position);
    plane.z() = kMarkerHeight;
    glyphs.push_back({plane, m.kind, m.status == MarkerStatus::Preview, m.label});
  }
  markers_->show(glyphs, kMarkerRadiusPixels * millimetresPerPixel(), millimetresPerPixel());
}

std::vector<std::size_t> SliceView::markersOnSlice(const MarkerSet& markers, std::uint64_t revision) {
  if (indexedRevision_ != revision) {
    markersByDepth_.clear();
    for (std::size_t i = 0; i < markers.markers.size(); ++i)
      if (hasPosition(markers.markers[i].status))
        markersByDepth_.emplace_back(frame_.toPlane(markers.markers[i].position).z(), i);
    std::sort(markersByDepth_.begin(), markersByDepth_.end());
    indexedRevision_ = revision;
  }
  // A little wider than half a step, then isOnSlice's own test, so that round-off decides as it does.
  const double reach = extent_.depthStep / 2 * (1 + 1e-9) + 1e-9 * std::abs(depth_);
  const auto first = std::lower_bound(markersByDepth_.begin(), markersByDepth_.end(),
                                      std::make_pair(depth_ - reach, std::size_t(0)));
  std::vector<std::size_t> onSlice;
  for (auto it = first; it != markersByDepth_.end() && it->first <= depth_ + reach; ++it)
    if (isOnSlice(markers.markers[it->second].position)) onSlice.push_back(it->second);
  std::sort(onSlice.begin(), onSlice.end());  // the document's order, as drawn before
  return onSlice;
}

vtkImageAlgorithm* SliceView::colouredSlice() const { return colours_; }

void SliceView::addLabelLayer(vtkImageData* indexSpaceLabels, vtkMatrix4x4* labelWorldToIndex,
                              vtkImageAlgorithm* labelColours) {
  auto reslice = vtkSmartPointer<vtkImageReslice>::New();
  reslice->SetInputData(indexSpaceLabels);
  reslice->SetOutputDimensionality(2);
  reslice->SetInterpolationModeToNearestNeighbor();
  reslice->SetOutputSpacing(reslice_->GetOutputSpacing());
  reslice->SetOutputOrigin(reslice_->GetOutputOrigin());
  reslice->SetOutputExtent(reslice_->GetOutputExtent());
  auto labelAxes = vtkSmartPointer<vtkMatrix4x4>::New();
  reslice->SetResliceAxes(labelAxes);
  labelColours->SetInputConnection(reslice->GetOutputPort());
  auto layer = vtkSmartPointer<vtkImageActor>::New();
  layer->GetMapper()->SetInputConnection(labelColours->GetOutputPort());
  layer->InterpolateOff();
  layer->SetPosition(0, 0, kLabelLayerHeight);
  renderer_->AddActor(layer);
  changed_ = true;
  vtkSmartPointer<vtkMatrix4x4> worldToIndex = labelWorldToIndex;
  auto follow = [this, reslice, labelAxes, worldToIndex] {
    vtkMatrix4x4::Multiply4x4(worldToIndex, planeToWorld_, labelAxes);
    reslice->Modified();
  };
  follow();
  onPlaneMoved_.push_back(follow);
}

void SliceView::addSurfaceContour(vtkPolyData* worldSurface, const Eigen::Vector3d& colour) {
  auto plane = vtkSmartPointer<vtkPlane>::New();
  auto cutter = vtkSmartPointer<vtkCutter>::New();
  cutter->SetInputData(worldSurface);
  cutter->SetCutFunction(plane);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(cutter->GetOutputPort());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(colour.x(), colour.y(), colour.z());
  actor->GetProperty()->SetLineWidth(2);
  actor->GetProperty()->SetAmbient(1.0);
  actor->GetProperty()->SetDiffuse(0.0);
  renderer_->AddActor(actor);
  changed_ = true;
  auto follow = [this, plane, actor] {
    const Eigen::Vector3d origin = frame_.toWorld(Eigen::Vector3d(0, 0, depth_));
    plane->SetOrigin(origin.data());
    plane->SetNormal(frame_.normal.data());
    actor->SetUserMatrix(liftedInverse(planeToWorld_, kContourHeight));
  };
  follow();
  onPlaneMoved_.push_back(follow);
}

void SliceView::updateSlicePlane() {
  changed_ = true;
  Eigen::Matrix4d planeToWorld = Eigen::Matrix4d::Identity();
  planeToWorld.topLeftCorner<3, 3>() = frame_.planeToWorld();
  planeToWorld.topRightCorner<3, 1>() = frame_.normal * depth_;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) planeToWorld_->SetElement(r, c, planeToWorld(r, c));
  vtkMatrix4x4::Multiply4x4(scan_.worldToIndex(), planeToWorld_, resliceAxes_);
  resliceAxes_->Modified();
  reslice_->Modified();
  for (auto& follow : onPlaneMoved_) follow();
  updateCrosshair();
  const std::string title = std::string(sliceAxisName(axis_)) + "  " +
                            slicePositionText(axis_, frame_.toWorld(Eigen::Vector3d(0, 0, depth_)));
  title_->SetInput(title.c_str());
}

void SliceView::updateCrosshair() {
  const Eigen::Vector2d low = extent_.centre.head<2>() - extent_.halfSize.head<2>();
  const Eigen::Vector2d high = extent_.centre.head<2>() + extent_.halfSize.head<2>();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->InsertNextPoint(low.x(), cursor_.y(), kCrosshairHeight);
  points->InsertNextPoint(high.x(), cursor_.y(), kCrosshairHeight);
  points->InsertNextPoint(cursor_.x(), low.y(), kCrosshairHeight);
  points->InsertNextPoint(cursor_.x(), high.y(), kCrosshairHeight);
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  const vtkIdType horizontal[2] = {0, 1}, vertical[2] = {2, 3};
  lines->InsertNextCell(2, horizontal);
  lines->InsertNextCell(2, vertical);
  crosshair_->SetPoints(points);
  crosshair_->SetLines(lines);
  crosshair_->Modified();
}

}  // namespace vesalius::picker
