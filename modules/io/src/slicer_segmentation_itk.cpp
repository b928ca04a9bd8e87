// ITK side of .seg.nrrd files (slicer_segmentation_itk.h): NrrdImageIO reads a 4-D segmentation's "list"
// axis as the components of a vector image, and keeps and writes "key:=value" fields in the image's
// metadata dictionary.
#include "slicer_segmentation_itk.h"

#include "vesalius/core/error.h"

#include <itkImageFileReader.h>
#include <itkImageFileWriter.h>
#include <itkMetaDataObject.h>
#include <itkNrrdImageIO.h>
#include <itkVectorImage.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace vesalius::io::itk_seam {

namespace {

itk::NrrdImageIO::Pointer openNrrd(const std::string& path) {
  auto io = itk::NrrdImageIO::New();
  if (!io->CanReadFile(path.c_str())) throw BadInput(path, "not a NRRD file ITK can read");
  io->SetFileName(path);
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(path, itkErrorReason(error));
  }
  for (unsigned axis = 3; axis < io->GetNumberOfDimensions(); ++axis)
    if (io->GetDimensions(axis) > 1)
      throw BadInput(path, std::to_string(io->GetNumberOfDimensions()) +
                               "-D segmentation beyond its layer axis; only 3-D layers are read");
  return io;
}

template <class T>
void readVoxels(const std::string& path, itk::NrrdImageIO* io, RawSegmentationFile& file) {
  using ImageType = itk::VectorImage<T, 3>;
  auto reader = itk::ImageFileReader<ImageType>::New();
  reader->SetFileName(path);
  reader->SetImageIO(io);
  try {
    reader->Update();
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(path, itkErrorReason(error));
  }
  const ImageType& image = *reader->GetOutput();
  const auto size = image.GetLargestPossibleRegion().GetSize();
  for (unsigned axis = 0; axis < 3; ++axis) {
    file.header.size[axis] = int(size[axis]);
    file.header.spacing[axis] = image.GetSpacing()[axis];
    file.header.origin[axis] = image.GetOrigin()[axis];
    for (unsigned column = 0; column < 3; ++column)
      file.header.direction[3 * axis + column] = image.GetDirection()(axis, column);
  }
  file.header.components = int(image.GetNumberOfComponentsPerPixel());
  const std::size_t count = image.GetLargestPossibleRegion().GetNumberOfPixels() * file.header.components;
  const T* buffer = image.GetBufferPointer();
  file.values.resize(count);
  for (std::size_t n = 0; n < count; ++n) {
    const double value = double(buffer[n]);
    if (!(value >= 0 && value <= 65535 && value == std::floor(value))) {
      const std::size_t voxel = n / file.header.components, nx = size[0], ny = size[1];
      std::ostringstream problem;
      problem << "voxel (" << voxel % nx << ", " << voxel / nx % ny << ", " << voxel / (nx * ny) << ") of layer "
              << n % file.header.components << " holds " << value
              << "; labels must be whole numbers from 0 to 65535";
      throw BadInput(path, problem.str());
    }
    file.values[n] = std::uint16_t(value);
  }
}

// NrrdImageIO says "Write: Error writing <file>:" and gives teem's chain of callers on the lines after it,
// the innermost (the actual failure) last: "[nrrd] _nrrdEncodingGzip_write: error compressing".
std::string writeFailure(const itk::ExceptionObject& error) {
  const std::string first = itkErrorReason(error);
  if (first.empty() || first.back() != ':') return first;
  std::istringstream lines(error.GetDescription());
  std::string line, reason;
  while (std::getline(lines, line)) {
    const std::size_t start = line.find_first_not_of(" \t\r");
    if (start == std::string::npos) continue;
    reason = line.substr(start);
    const std::size_t tag = reason.find("] ");
    if (reason.front() == '[' && tag != std::string::npos) reason = reason.substr(tag + 2);  // "[nrrd] "
  }
  while (!reason.empty() && (reason.back() == '\r' || reason.back() == ' ')) reason.pop_back();
  return reason.empty() || reason == first ? "ITK's NRRD writer failed" : reason;
}

template <class T>
void writeAs(const std::string& path, const RawHeader& header,
             const std::vector<std::pair<std::string, std::string>>& fields, const std::vector<std::uint16_t>& values) {
  using ImageType = itk::Image<T, 3>;
  auto image = ImageType::New();
  typename ImageType::RegionType region;
  typename ImageType::SpacingType spacing;
  typename ImageType::PointType origin;
  typename ImageType::DirectionType direction;
  for (unsigned axis = 0; axis < 3; ++axis) {
    region.SetSize(axis, itk::SizeValueType(header.size[axis]));
    spacing[axis] = header.spacing[axis];
    origin[axis] = header.origin[axis];
    for (unsigned column = 0; column < 3; ++column) direction(axis, column) = header.direction[3 * axis + column];
  }
  image->SetRegions(region);
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  image->SetDirection(direction);
  image->Allocate();
  std::transform(values.begin(), values.end(), image->GetBufferPointer(), [](std::uint16_t v) { return T(v); });
  itk::MetaDataDictionary& dictionary = image->GetMetaDataDictionary();
  for (const auto& [key, value] : fields) itk::EncapsulateMetaData<std::string>(dictionary, key, value);

  auto writer = itk::ImageFileWriter<ImageType>::New();
  writer->SetFileName(path);
  writer->SetImageIO(itk::NrrdImageIO::New());
  writer->SetInput(image);
  writer->SetUseCompression(true);
  try {
    writer->Update();
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(path, "cannot write: " + writeFailure(error));
  }
}

}  // namespace

RawSegmentationFile readSegmentationFile(const std::string& path) {
  registerImageFactories();
  itk::NrrdImageIO::Pointer io = openNrrd(path);
  RawSegmentationFile file;
  const itk::MetaDataDictionary& dictionary = io->GetMetaDataDictionary();
  for (const std::string& key : dictionary.GetKeys()) {
    std::string value;
    if (key.rfind("Segment", 0) == 0 && itk::ExposeMetaData<std::string>(dictionary, key, value))
      file.fields.emplace_back(key, value);
  }
  const auto component = io->GetComponentType();
  if (component == itk::IOComponentEnum::UCHAR || component == itk::IOComponentEnum::USHORT) {
    readVoxels<std::uint16_t>(path, io, file);
  } else {
    // Other types may hold fractions, negatives or large values: read exactly, then check each voxel.
    readVoxels<double>(path, io, file);
  }
  return file;
}

void writeSegmentationFile(const std::string& path, const RawHeader& header,
                           const std::vector<std::pair<std::string, std::string>>& fields,
                           const std::vector<std::uint16_t>& values) {
  registerImageFactories();
  const std::uint16_t largest = values.empty() ? 0 : *std::max_element(values.begin(), values.end());
  if (largest < 256)
    writeAs<std::uint8_t>(path, header, fields, values);
  else
    writeAs<std::uint16_t>(path, header, fields, values);
  // ITK's writers report some failures (a full disk) on stderr only: read back what was written.
  RawSegmentationFile back;
  try {
    back = readSegmentationFile(path);
  } catch (const BadInput& error) {
    throw BadInput(path, "cannot write: the file written does not read back (" + error.problem() +
                             "); is the disk full?");
  }
  if (back.values != values)
    throw BadInput(path, "cannot write: the file written does not hold every voxel; is the disk full?");
}

}  // namespace vesalius::io::itk_seam
