// Markers drawn in one renderer: one actor per marker kind and status (placed or preview), so 5,000
// markers cost six actors, not 5,000, plus one for the labels. Slice views draw discs with a glyph
// mapper and labels from cached bitmaps (slice_labels.h); the 3D view draws each marker as one point
// rendered as a sphere by the GPU, which keeps thousands of them cheap, and labels with
// vtkLabeledDataMapper (which rasterises them at every render; the 3D view is not rendered per slice
// step). Previews (suggestions to accept or reject) are rings of their kind's colour in the slices and
// dimmer spheres in 3D. The caller decides which markers to show and where (a slice
// view passes the ones on its slice in plane coordinates; the 3D view passes all of them in world space).
#pragma once

#include "slice_labels.h"

#include "vesalius/core/markers.h"

#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

class vtkActor;
class vtkActor2D;
class vtkPolyData;
class vtkRenderer;

namespace vesalius::picker {

// Each kind's colour (RGB in 0..1): landmarks yellow, ICP markers cyan, attachments magenta.
Eigen::Vector3d markerKindColour(MarkerKind kind);

struct MarkerGlyph {
  Eigen::Vector3d position;  // in the renderer's coordinates
  MarkerKind kind = MarkerKind::Landmark;
  bool preview = false;  // a suggestion not yet accepted
  std::string label;     // empty: no label
};

// Flat discs facing +z, sized in the renderer's units (slices); spheres of a fixed size on screen (3D).
enum class GlyphShape { Disc, ScreenSphere };

class MarkerLayer {
 public:
  MarkerLayer(vtkRenderer* renderer, GlyphShape shape);
  ~MarkerLayer();

  // Replaces what is drawn. `radius`: the disc radius in the renderer's units (mm); labels sit that far
  // and a half to the right of their marker. `millimetresPerPixel`: the scale of a slice view (discs).
  void show(const std::vector<MarkerGlyph>& glyphs, double radius, double millimetresPerPixel = 1);

 private:
  // Indexed by kind + 3 * preview.
  std::array<vtkSmartPointer<vtkPolyData>, 6> pointsPerGroup_;
  std::array<vtkSmartPointer<vtkActor>, 6> actorsPerGroup_;
  GlyphShape shape_;
  std::unique_ptr<SliceLabels> sliceLabels_;  // discs
  vtkSmartPointer<vtkPolyData> labelAnchors_;  // screen spheres
  vtkSmartPointer<vtkActor2D> labelActor_;
};

}  // namespace vesalius::picker
