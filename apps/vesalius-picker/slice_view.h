// One slice view: a world-aligned plane through the scan (axial, coronal or sagittal), resampled with
// vtkImageReslice through the scan's world -> index map, shown in a parallel-projection camera.
//
// The renderer works in the plane's own coordinates (slice_geometry.h): x right, y up, the image at z = 0
// and overlays above it (toward the camera). A display pixel maps to the plane point
//   centre + (pixel - viewport centre) * 2 * parallelScale / viewport height,
// and that plane point at the current depth to the LPS world point SliceFrame::toWorld.
#pragma once

#include "marker_layer.h"
#include "scan_volume.h"
#include "slice_geometry.h"
#include "window_level.h"

#include <vtkMatrix4x4.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

class vtkActor;
class vtkImageActor;
class vtkImageAlgorithm;
class vtkImageMapToWindowLevelColors;
class vtkImageReslice;
class vtkPolyData;
class vtkRenderWindow;
class vtkTextActor;

namespace vesalius::picker {

class SliceView {
 public:
  // `viewport`: xmin, ymin, xmax, ymax as fractions of the window.
  SliceView(SliceAxis axis, const ScanVolume& scan, vtkRenderWindow* window,
            const std::array<double, 4>& viewport);
  ~SliceView();

  const SliceFrame& frame() const { return frame_; }
  vtkRenderer* renderer() const { return renderer_; }
  bool contains(int displayX, int displayY) const;
  // Whether anything drawn changed since the last call (the window then skips rendering this view).
  bool takeChanged() { return std::exchange(changed_, false); }

  void stepSlices(int steps);  // positive: toward frame().forward; clamped to the scan
  void showSliceThrough(const Eigen::Vector3d& world);  // depth to the point's, crosshair on it

  // The world point under a display pixel, on the current slice.
  Eigen::Vector3d displayToWorld(int displayX, int displayY) const;
  double millimetresPerPixel() const;
  bool isOnSlice(const Eigen::Vector3d& world) const;  // within half a slice step of it

  void zoom(double factor);  // > 1 magnifies
  void pan(int dxPixels, int dyPixels);
  void fitToScan();
  void setWindowLevel(const WindowLevel& windowLevel);

  // Redraws the markers on this slice (previews as rings), sized a fixed number of pixels; nothing to do
  // when the markers' `revision`, the slice and the zoom are those last drawn, so that a view whose
  // content did not change is not rendered again. The markers of a slice come from an index sorted by
  // depth, rebuilt when `revision` changes, not from a scan of every marker at every slice step.
  void showMarkers(const MarkerSet& markers, std::uint64_t revision);
  // The coloured slice image (for the 3D view) and the map from its plane coordinates to world.
  vtkImageAlgorithm* colouredSlice() const;
  vtkMatrix4x4* planeToWorld() const { return planeToWorld_; }
  // Adds a translucent label-colour layer, resliced on this view's pixels (nearest neighbour) through
  // the label map's own world -> index map, so it may lie on another grid than the scan.
  void addLabelLayer(vtkImageData* indexSpaceLabels, vtkMatrix4x4* labelWorldToIndex,
                     vtkImageAlgorithm* labelColours);
  // Adds the contour of a world-space surface where it cuts this slice.
  void addSurfaceContour(vtkPolyData* worldSurface, const Eigen::Vector3d& colour);

 private:
  void updateSlicePlane();
  void updateCrosshair();
  std::vector<std::size_t> markersOnSlice(const MarkerSet& markers, std::uint64_t revision);

  SliceAxis axis_;
  SliceFrame frame_;
  SliceExtent extent_;
  const ScanVolume& scan_;
  double depth_ = 0;
  Eigen::Vector2d cursor_ = Eigen::Vector2d::Zero();  // crosshair, plane coordinates
  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkMatrix4x4> planeToWorld_, resliceAxes_;
  vtkSmartPointer<vtkImageReslice> reslice_;
  vtkSmartPointer<vtkImageMapToWindowLevelColors> colours_;
  vtkSmartPointer<vtkImageActor> image_;
  vtkSmartPointer<vtkPolyData> crosshair_;
  vtkSmartPointer<vtkTextActor> title_;
  std::vector<std::function<void()>> onPlaneMoved_;  // overlays that follow the slice
  std::unique_ptr<MarkerLayer> markers_;
  std::optional<std::tuple<std::uint64_t, double, double>> drawnMarkers_;  // revision, depth, mm per pixel
  std::optional<std::uint64_t> indexedRevision_;
  std::vector<std::pair<double, std::size_t>> markersByDepth_;  // (depth, index), sorted
  bool changed_ = true;
};

}  // namespace vesalius::picker
