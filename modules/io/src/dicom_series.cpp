// ITK side of DICOM folders: which series a folder holds and which files make each one, through GDCM.
// Exchanges plain data only (see image_io_itk.h for why).
#include "vesalius/io/dicom_series.h"

#include "image_io_itk.h"

#include "vesalius/core/error.h"

#include <itkGDCMImageIO.h>
#include <itkGDCMSeriesFileNames.h>

#include <filesystem>

namespace vesalius::io::itk_seam {

namespace {

std::string tagValue(itk::GDCMImageIO& io, const char* tag) {
  std::string value;
  io.GetValueFromTag(tag, value);
  const std::size_t end = value.find_last_not_of(" \0", std::string::npos, 2);
  return end == std::string::npos ? std::string() : value.substr(0, end + 1);
}

// Series description and modality from the header of the series' first file; left empty if unreadable,
// since they only help a person choose.
void describeSeries(RawDicomSeries& series) {
  auto io = itk::GDCMImageIO::New();
  io->SetFileName(series.files.front());
  try {
    io->ReadImageInformation();
  } catch (const itk::ExceptionObject&) {
    return;
  }
  series.description = tagValue(*io, "0008|103e");
  series.modality = tagValue(*io, "0008|0060");
}

// GDCMSeriesFileNames prints a multi-line ITK warning for a folder without DICOM files; look first.
bool holdsDicomFile(const std::string& folder) {
  std::error_code error;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(folder, error))
    if (entry.is_regular_file(error) && isDicomFile(entry.path().string())) return true;
  return false;
}

}  // namespace

bool isDicomFile(const std::string& path) {
  auto io = itk::GDCMImageIO::New();
  return io->CanReadFile(path.c_str());
}

std::vector<RawDicomSeries> findDicomSeries(const std::string& folder) {
  registerImageFactories();
  std::vector<RawDicomSeries> found;
  if (!holdsDicomFile(folder)) return found;
  try {
    auto names = itk::GDCMSeriesFileNames::New();
    // Plain series instance UIDs, so the UID a user copies from a DICOM viewer selects the series.
    names->SetUseSeriesDetails(false);
    names->SetRecursive(false);
    names->SetInputDirectory(folder);
    for (const std::string& uid : names->GetSeriesUIDs()) {
      RawDicomSeries series;
      series.uid = uid;
      series.files = names->GetFileNames(uid);
      if (series.files.empty()) continue;
      describeSeries(series);
      found.push_back(std::move(series));
    }
  } catch (const itk::ExceptionObject& error) {
    throw BadInput(folder, itkErrorReason(error));
  }
  return found;
}

}  // namespace vesalius::io::itk_seam

namespace vesalius::io {

std::vector<DicomSeries> listDicomSeries(const std::string& folder) {
  std::vector<DicomSeries> listed;
  for (const itk_seam::RawDicomSeries& series : itk_seam::findDicomSeries(folder))
    listed.push_back(DicomSeries{series.uid, int(series.files.size()), series.description, series.modality});
  return listed;
}

}  // namespace vesalius::io
