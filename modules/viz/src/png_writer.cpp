// PNG files from RgbImage through vtkPNGWriter (rgb_image.h).
#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/viz/rgb_image.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <string_view>

namespace vesalius::viz {
namespace {

// VTK images have row 0 at the bottom; RgbImage has it at the top.
vtkSmartPointer<vtkImageData> toVtk(const RgbImage& image) {
  auto data = vtkSmartPointer<vtkImageData>::New();
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* out = static_cast<std::uint8_t*>(data->GetScalarPointer());
  const std::size_t rowBytes = std::size_t(image.width) * 3;
  for (int y = 0; y < image.height; ++y) {
    const auto row = image.pixels.begin() + std::ptrdiff_t(rowBytes * std::size_t(y));
    std::copy(row, row + std::ptrdiff_t(rowBytes), out + rowBytes * std::size_t(image.height - 1 - y));
  }
  return data;
}

}  // namespace

void writePng(const std::string& path, const RgbImage& image, const WriteOptions& options) {
  if (image.width <= 0 || image.height <= 0) throw UsageError("cannot write an empty picture to " + path);
  const vtkSmartPointer<vtkImageData> data = toVtk(image);
  writeAtomically(path, options, [&](const std::string& temporary) {
    // Encoded in memory and written by us: on a full disk libpng and VTK would each print their own
    // lines on stderr before ours.
    vtkNew<vtkPNGWriter> writer;
    writer->WriteToMemoryOn();
    writer->SetInputData(data);
    writer->Write();
    vtkUnsignedCharArray* png = writer->GetResult();
    if (writer->GetErrorCode() != 0 || !png || png->GetNumberOfValues() == 0)
      throw BadInput(path, "cannot encode the PNG file");
    writeFileBytes(temporary, std::string_view(reinterpret_cast<const char*>(png->GetPointer(0)),
                                               std::size_t(png->GetNumberOfValues())));
  });
}

}  // namespace vesalius::viz
