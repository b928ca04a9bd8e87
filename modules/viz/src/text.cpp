// Text into RgbImage with vtkFreeTypeTools (text.h): FreeType rasterises to an RGBA vtkImageData, which is
// blended by its alpha. No render window is involved, so this works without X.
#include "vesalius/viz/text.h"

#include "vesalius/core/error.h"

#include <vtkFreeTypeTools.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkStdString.h>
#include <vtkTextProperty.h>

namespace vesalius::viz {
namespace {

constexpr int kDpi = 72;  // at 72 dpi a font size in points is a size in pixels

vtkNew<vtkTextProperty> textProperty(int pixelSize) {
  vtkNew<vtkTextProperty> property;
  property->SetFontFamilyToArial();
  property->SetFontSize(pixelSize);
  property->SetColor(1.0, 1.0, 1.0);
  property->SetJustificationToLeft();
  property->SetVerticalJustificationToBottom();
  return property;
}

}  // namespace

TextExtent measureText(const std::string& text, int pixelSize) {
  if (text.empty()) return {};
  vtkNew<vtkTextProperty> property = textProperty(pixelSize);
  int box[4];
  if (!vtkFreeTypeTools::GetInstance()->GetBoundingBox(property.Get(), vtkStdString(text), kDpi, box))
    throw NumericalFailure("FreeType could not measure the text \"" + text + "\"");
  return {box[1] - box[0] + 1, box[3] - box[2] + 1};
}

void drawText(RgbImage& image, int x, int y, const std::string& text, const Rgb& color, int pixelSize) {
  if (text.empty()) return;
  vtkNew<vtkTextProperty> property = textProperty(pixelSize);
  vtkFreeTypeTools* freeType = vtkFreeTypeTools::GetInstance();
  freeType->ScaleToPowerTwoOff();
  vtkNew<vtkImageData> glyphs;
  int dims[2] = {0, 0};
  if (!freeType->RenderString(property.Get(), vtkStdString(text), kDpi, glyphs.Get(), dims))
    throw NumericalFailure("FreeType could not draw the text \"" + text + "\"");
  int extent[6];
  glyphs->GetExtent(extent);
  // The rendered rows run bottom to top; the text occupies the first dims[1] of them.
  for (int row = 0; row < dims[1]; ++row)
    for (int col = 0; col < dims[0]; ++col) {
      const auto* rgba = static_cast<const unsigned char*>(
          glyphs->GetScalarPointer(extent[0] + col, extent[2] + row, extent[4]));
      if (rgba[3] > 0) image.blend(x + col, y + dims[1] - 1 - row, color, rgba[3] / 255.0);
    }
}

}  // namespace vesalius::viz
