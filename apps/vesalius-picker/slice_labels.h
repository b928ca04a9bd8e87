// Marker labels in a slice view, drawn as one textured actor. vtkLabeledDataMapper rasterises every label
// with FreeType and draws it with a mapper of its own at every render: with 5,000 markers, some fifty labels
// on each slice took 70 % of a slice step's time (perf; docs/benchmarks.md). Here each label's text is
// rasterised once (cached by its text) and, when the labels shown change, their cached bitmaps are stacked
// into one texture drawn as one quad per label: a slice step copies a few small bitmaps and draws once.
// The quads lie in the renderer's world coordinates (a slice view's plane, parallel projection), one
// texel per screen pixel at the view's current scale, so show() is called again when the scale changes;
// they are drawn as an overlay, over the markers and the image.
#pragma once

#include <vtkSmartPointer.h>

#include <Eigen/Core>

#include <string>
#include <unordered_map>
#include <vector>

class vtkImageData;
class vtkPolyData;
class vtkRenderer;
class vtkTextProperty;
class vtkTexture;
class vtkTexturedActor2D;

namespace vesalius::picker {

struct SliceLabel {
  Eigen::Vector3d anchor;  // renderer coordinates: the text starts here, centred on it vertically
  std::string text;
};

class SliceLabels {
 public:
  // `text`: font, size, colour and shadow; justification is left and centred vertically.
  SliceLabels(vtkRenderer* renderer, vtkTextProperty* text);
  ~SliceLabels();

  // Replaces the labels drawn; `millimetresPerPixel`: the renderer's scale.
  void show(const std::vector<SliceLabel>& labels, double millimetresPerPixel);

 private:
  // The label's bitmap: RGBA, extent relative to the anchor in pixels; the text fills `size` texels
  // from the extent's lower-left corner.
  struct Bitmap {
    vtkSmartPointer<vtkImageData> image;
    Eigen::Vector2i size = Eigen::Vector2i::Zero();
  };
  const Bitmap& bitmap(const std::string& text);

  vtkSmartPointer<vtkTextProperty> text_;
  int dpi_ = 72;
  std::unordered_map<std::string, Bitmap> cache_;
  vtkSmartPointer<vtkPolyData> quads_;
  vtkSmartPointer<vtkTexture> texture_;
  vtkSmartPointer<vtkTexturedActor2D> actor_;
};

}  // namespace vesalius::picker
