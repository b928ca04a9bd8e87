#include "slice_labels.h"

#include <vtkCellArray.h>
#include <vtkCoordinate.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper2D.h>
#include <vtkProperty2D.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkTextProperty.h>
#include <vtkTextRenderer.h>
#include <vtkTexture.h>
#include <vtkTexturedActor2D.h>

#include <algorithm>
#include <cstring>

namespace vesalius::picker {

SliceLabels::SliceLabels(vtkRenderer* renderer, vtkTextProperty* text) {
  text_ = vtkSmartPointer<vtkTextProperty>::New();
  text_->ShallowCopy(text);
  text_->SetJustificationToLeft();
  text_->SetVerticalJustificationToCentered();
  if (renderer->GetRenderWindow()) dpi_ = renderer->GetRenderWindow()->GetDPI();
  quads_ = vtkSmartPointer<vtkPolyData>::New();
  // An overlay (as vtkTextActor draws its text) with its corners in world coordinates: blended over the
  // view without the order-independent translucency pass a translucent 3D actor costs every render.
  auto world = vtkSmartPointer<vtkCoordinate>::New();
  world->SetCoordinateSystemToWorld();
  auto mapper = vtkSmartPointer<vtkPolyDataMapper2D>::New();
  mapper->SetInputData(quads_);
  mapper->SetTransformCoordinate(world);
  mapper->ScalarVisibilityOff();
  texture_ = vtkSmartPointer<vtkTexture>::New();
  texture_->InterpolateOff();  // one texel per pixel: crisp text
  texture_->RepeatOff();
  texture_->EdgeClampOn();
  actor_ = vtkSmartPointer<vtkTexturedActor2D>::New();
  actor_->SetMapper(mapper);
  actor_->SetTexture(texture_);
  actor_->GetProperty()->SetColor(1, 1, 1);  // the texture's own colours
  actor_->VisibilityOff();
  renderer->AddActor2D(actor_);
}

SliceLabels::~SliceLabels() = default;

const SliceLabels::Bitmap& SliceLabels::bitmap(const std::string& text) {
  const auto cached = cache_.find(text);
  if (cached != cache_.end()) return cached->second;
  Bitmap b;
  b.image = vtkSmartPointer<vtkImageData>::New();
  int size[2] = {0, 0};
  vtkTextRenderer* freeType = vtkTextRenderer::GetInstance();
  // A bitmap that is not RGBA bytes (no text renderer, an empty string) stays unlabelled: size 0.
  if (freeType && freeType->RenderString(text_, text, b.image, size, dpi_) &&
      b.image->GetScalarType() == VTK_UNSIGNED_CHAR && b.image->GetNumberOfScalarComponents() == 4)
    b.size = Eigen::Vector2i(size[0], size[1]);
  return cache_.emplace(text, b).first->second;
}

void SliceLabels::show(const std::vector<SliceLabel>& labels, double millimetresPerPixel) {
  std::vector<const Bitmap*> bitmaps;
  int width = 1, height = 0;
  for (const SliceLabel& label : labels) {
    bitmaps.push_back(&bitmap(label.text));
    width = std::max(width, bitmaps.back()->size.x());
    height += bitmaps.back()->size.y();
  }
  actor_->SetVisibility(height > 0);
  if (height == 0) return;

  // The bitmaps stacked bottom to top in one texture; a quad per label shows its rows.
  auto atlas = vtkSmartPointer<vtkImageData>::New();
  atlas->SetDimensions(width, height, 1);
  atlas->AllocateScalars(VTK_UNSIGNED_CHAR, 4);
  auto* texels = static_cast<unsigned char*>(atlas->GetScalarPointer());
  std::memset(texels, 0, std::size_t(width) * std::size_t(height) * 4);
  auto points = vtkSmartPointer<vtkPoints>::New();
  auto quads = vtkSmartPointer<vtkCellArray>::New();
  auto uv = vtkSmartPointer<vtkFloatArray>::New();
  uv->SetNumberOfComponents(2);
  int row = 0;
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const Bitmap& b = *bitmaps[i];
    if (b.size.y() == 0) continue;
    const int* extent = b.image->GetExtent();
    for (int y = 0; y < b.size.y(); ++y)
      std::memcpy(texels + 4 * (std::size_t(row + y) * std::size_t(width)),
                  b.image->GetScalarPointer(extent[0], extent[2] + y, extent[4]), 4 * std::size_t(b.size.x()));
    const Eigen::Vector3d low = labels[i].anchor + millimetresPerPixel * Eigen::Vector3d(extent[0], extent[2], 0);
    const Eigen::Vector3d span = millimetresPerPixel * Eigen::Vector3d(b.size.x(), b.size.y(), 0);
    const float u = float(b.size.x()) / float(width), v0 = float(row) / float(height),
                v1 = float(row + b.size.y()) / float(height);
    const vtkIdType first = points->GetNumberOfPoints();
    points->InsertNextPoint(low.x(), low.y(), low.z());
    points->InsertNextPoint(low.x() + span.x(), low.y(), low.z());
    points->InsertNextPoint(low.x() + span.x(), low.y() + span.y(), low.z());
    points->InsertNextPoint(low.x(), low.y() + span.y(), low.z());
    for (const auto& [s, t] : {std::pair{0.0f, v0}, std::pair{u, v0}, std::pair{u, v1}, std::pair{0.0f, v1}})
      uv->InsertNextTuple2(s, t);
    const vtkIdType corners[4] = {first, first + 1, first + 2, first + 3};
    quads->InsertNextCell(4, corners);
    row += b.size.y();
  }
  quads_->SetPoints(points);
  quads_->SetPolys(quads);
  quads_->GetPointData()->SetTCoords(uv);
  quads_->Modified();
  texture_->SetInputData(atlas);
}

}  // namespace vesalius::picker
