// What the DCMTK-based DICOM files share (dicom_common.h).
#include "dicom_common.h"

#include "image_io_itk.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcmetinf.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/oflog/oflog.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>

namespace vesalius::io::dicom {

void quietDcmtk() {
  static std::once_flag once;
  std::call_once(once, [] { OFLog::configure(OFLogger::FATAL_LOG_LEVEL); });
}

void check(const OFCondition& condition, const std::string& path, const std::string& what) {
  if (condition.bad()) throw BadInput(path, what + ": " + condition.text());
}

std::string text(DcmItem& item, const DcmTagKey& tag) {
  OFString value;
  if (item.findAndGetOFStringArray(tag, value).bad()) return {};
  return value.c_str();
}

std::string decimal(double value) {
  if (std::abs(value) < 1e-12) value = 0;
  char buffer[40];
  for (int digits = 15; digits > 1; --digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (std::string(buffer).size() <= 16) break;
  }
  return buffer;
}

std::optional<Eigen::Vector3d> imagePosition(DcmItem& item) {
  Eigen::Vector3d p;
  for (int c = 0; c < 3; ++c)
    if (item.findAndGetFloat64(DCM_ImagePositionPatient, p[c], c).bad()) return std::nullopt;
  return p;
}

DicomSourceSeries sourceAttributes(DcmItem& data) {
  DicomSourceSeries s;
  s.studyInstanceUid = text(data, DCM_StudyInstanceUID);
  s.seriesInstanceUid = text(data, DCM_SeriesInstanceUID);
  s.frameOfReferenceUid = text(data, DCM_FrameOfReferenceUID);
  s.patientName = text(data, DCM_PatientName);
  s.patientId = text(data, DCM_PatientID);
  s.patientBirthDate = text(data, DCM_PatientBirthDate);
  s.patientSex = text(data, DCM_PatientSex);
  s.studyDate = text(data, DCM_StudyDate);
  s.studyTime = text(data, DCM_StudyTime);
  s.studyId = text(data, DCM_StudyID);
  s.accessionNumber = text(data, DCM_AccessionNumber);
  s.referringPhysicianName = text(data, DCM_ReferringPhysicianName);
  s.studyDescription = text(data, DCM_StudyDescription);
  return s;
}

void loadDicom(DcmFileFormat& file, const std::string& path, bool withPixels) {
  quietDcmtk();
  itk_seam::checkDicomFileStructure(path);
  const OFCondition status =
      withPixels ? file.loadFile(path.c_str()) : file.loadFileUntilTag(path.c_str(), EXS_Unknown, EGL_noChange,
                                                                       DCM_MaxReadLength, ERM_autoDetect, DCM_PixelData);
  if (status.bad()) throw BadInput(path, std::string("not a readable DICOM file: ") + status.text());
}

std::string sopClassOf(DcmFileFormat& file) {
  std::string uid = text(*file.getDataset(), DCM_SOPClassUID);
  return uid.empty() ? text(*file.getMetaInfo(), DCM_MediaStorageSOPClassUID) : uid;
}

bool isDicomFileOfClass(const std::string& path, const std::string& sopClass) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  if (fileExtension(path) != ".dcm" && !itk_seam::hasDicomPreamble(path)) return false;
  try {
    DcmFileFormat file;
    loadDicom(file, path, false);
    return sopClassOf(file) == sopClass;
  } catch (const BadInput&) {
    return false;
  }
}

std::string labelDescription(Label id) { return "label " + std::to_string(id); }

Label labelOfDescription(const std::string& d) {
  if (d.rfind("label ", 0) != 0 || d.size() <= 6 || d.size() > 11 ||
      d.find_first_not_of("0123456789", 6) != std::string::npos)
    return 0;
  const long id = std::stol(d.substr(6));
  return id >= 1 && id <= 65535 ? Label(id) : 0;
}

std::string newUid() {
  char uid[100];
  return dcmGenerateUniqueIdentifier(uid, SITE_INSTANCE_UID_ROOT);
}

const DicomSourceImage* sourceImageAt(const DicomSourceSeries* source, const GridGeometry& g, int k) {
  if (!source || source->seriesInstanceUid.empty()) return nullptr;
  const Eigen::Vector3d normal = g.direction.col(0).cross(g.direction.col(1)).normalized();
  const double at = normal.dot(g.indexToWorld(Eigen::Vector3d(0, 0, k)));
  const double step = std::abs(normal.dot(g.direction.col(2))) * g.spacing.z();
  const DicomSourceImage* best = nullptr;
  double bestDistance = 0.25 * step;
  for (const DicomSourceImage& image : source->images) {
    if (!image.position || image.sopInstanceUid.empty()) continue;
    const double distance = std::abs(normal.dot(*image.position) - at);
    if (distance <= bestDistance) best = &image, bestDistance = distance;
  }
  return best;
}

void saveWhole(DcmFileFormat& file, E_TransferSyntax syntax, const std::string& path, const std::string& reportedPath,
               const std::string& what) {
  check(file.saveFile(path.c_str(), syntax), reportedPath, "cannot write the " + what);
  const Uint32 expected = file.calcElementLength(syntax, EET_ExplicitLength);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error || size < expected)
    throw BadInput(reportedPath, "the " + what + " was not written whole (" + std::to_string(size) + " of " +
                                     std::to_string(expected) + " bytes)");
}

}  // namespace vesalius::io::dicom
