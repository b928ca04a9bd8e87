// DICOM SEG objects through DCMTK (dicom_seg.h). DCMTK reports problems through OFCondition; its own log is
// silenced, so a problem reaches the user once, as a BadInput naming the file.
#include "vesalius/io/dicom_seg.h"

#include "dicom_common.h"
#include "image_io_itk.h"

#include "vesalius/core/error.h"
#include "vesalius/io/dicom_rtstruct.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgfracon.h>
#include <dcmtk/dcmfg/fgpixmsr.h>
#include <dcmtk/dcmfg/fgplanor.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmfg/fgseg.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmiod/iodmacro.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

namespace vesalius::io {

namespace {

namespace fs = std::filesystem;
using namespace dicom;

// The SOP class and instance UIDs of an image: the dataset's, else the file meta header's (some
// anonymisers empty the dataset's and keep the meta header's).
DicomSourceImage sourceImageOf(DcmFileFormat& file) {
  DicomSourceImage image;
  DcmDataset& data = *file.getDataset();
  DcmMetaInfo& meta = *file.getMetaInfo();
  image.sopClassUid = text(data, DCM_SOPClassUID);
  if (image.sopClassUid.empty()) image.sopClassUid = text(meta, DCM_MediaStorageSOPClassUID);
  image.sopInstanceUid = text(data, DCM_SOPInstanceUID);
  if (image.sopInstanceUid.empty()) image.sopInstanceUid = text(meta, DCM_MediaStorageSOPInstanceUID);
  image.position = imagePosition(data);
  return image;
}

DicomSourceSeries seriesOfFiles(const std::vector<std::string>& files) {
  DicomSourceSeries series;
  for (std::size_t n = 0; n < files.size(); ++n) {
    DcmFileFormat file;
    loadDicom(file, files[n], false);
    if (n == 0) series = sourceAttributes(*file.getDataset());
    series.images.push_back(sourceImageOf(file));
  }
  return series;
}

// ---------------------------------------------------------------------------------------------- writing

const CodeSequenceMacro kTissue("85756007", "SCT", "Tissue");

struct SliceFrames {
  std::vector<std::vector<int>> slicesOfSegment;  // per present label, the slices holding it
  std::vector<Label> ids;                         // present labels, ascending
};

SliceFrames framesOf(const Grid<Label>& labels) {
  const GridGeometry& g = labels.geometry;
  const std::int64_t sliceSize = std::int64_t(g.size.x()) * g.size.y();
  std::vector<std::vector<bool>> inSlice(65536);
  for (std::int64_t n = 0; n < std::int64_t(labels.values.size()); ++n) {
    const Label id = labels.values[n];
    if (id == 0) continue;
    if (inSlice[id].empty()) inSlice[id].assign(g.size.z(), false);
    inSlice[id][n / sliceSize] = true;
  }
  SliceFrames frames;
  for (std::size_t id = 1; id < inSlice.size(); ++id) {
    if (inSlice[id].empty()) continue;
    frames.ids.push_back(Label(id));
    frames.slicesOfSegment.emplace_back();
    for (int k = 0; k < g.size.z(); ++k)
      if (inSlice[id][k]) frames.slicesOfSegment.back().push_back(k);
  }
  return frames;
}

void checkGrid(const GridGeometry& g, const std::string& path) {
  if (g.size.x() > 65535 || g.size.y() > 65535)
    throw BadInput(path, "a DICOM image holds at most 65535 rows and columns; the label map is " +
                             std::to_string(g.size.x()) + " x " + std::to_string(g.size.y()) + " per slice");
  const Eigen::Vector3d i = g.direction.col(0).normalized(), j = g.direction.col(1).normalized();
  if (std::abs(i.dot(j)) > 1e-4)
    throw BadInput(path, "the label map's i and j axes are not perpendicular; DICOM rows and columns must be");
}

void setSourceModules(DcmSegmentation& seg, const DicomSourceSeries& s, const std::string& path) {
  auto set = [&](const OFCondition& c, const char* what) { check(c, path, std::string("cannot set ") + what); };
  IODPatientModule& patient = seg.getPatient();
  set(patient.setPatientName(s.patientName.c_str(), false), "Patient's Name");
  set(patient.setPatientID(s.patientId.c_str(), false), "Patient ID");
  set(patient.setPatientBirthDate(s.patientBirthDate.c_str(), false), "Patient's Birth Date");
  set(patient.setPatientSex(s.patientSex.c_str(), false), "Patient's Sex");
  IODGeneralStudyModule& study = seg.getStudy();
  if (!s.studyInstanceUid.empty()) set(study.setStudyInstanceUID(s.studyInstanceUid.c_str()), "Study Instance UID");
  set(study.setStudyDate(s.studyDate.c_str(), false), "Study Date");
  set(study.setStudyTime(s.studyTime.c_str(), false), "Study Time");
  set(study.setStudyID(s.studyId.c_str(), false), "Study ID");
  set(study.setAccessionNumber(s.accessionNumber.c_str(), false), "Accession Number");
  set(study.setReferringPhysicianName(s.referringPhysicianName.c_str(), false), "Referring Physician's Name");
  set(study.setStudyDescription(s.studyDescription.c_str(), false), "Study Description");
  if (!s.frameOfReferenceUid.empty())
    set(seg.getFrameOfReference().setFrameOfReferenceUID(s.frameOfReferenceUid.c_str()), "Frame of Reference UID");
}

void addSharedGeometry(DcmSegmentation& seg, const GridGeometry& g, const std::string& path) {
  const Eigen::Vector3d i = g.direction.col(0).normalized(), j = g.direction.col(1).normalized();
  std::unique_ptr<FGPlaneOrientationPatient> orientation(FGPlaneOrientationPatient::createMinimal(
      decimal(i.x()).c_str(), decimal(i.y()).c_str(), decimal(i.z()).c_str(), decimal(j.x()).c_str(),
      decimal(j.y()).c_str(), decimal(j.z()).c_str()));
  if (!orientation) throw BadInput(path, "cannot write the image orientation");
  check(seg.addForAllFrames(*orientation), path, "cannot write the image orientation");
  FGPixelMeasures measures;
  // Pixel Spacing is (between rows, between columns): j then i.
  check(measures.setPixelSpacing((decimal(g.spacing.y()) + "\\" + decimal(g.spacing.x())).c_str()), path,
        "cannot write the pixel spacing");
  check(measures.setSliceThickness(decimal(g.spacing.z()).c_str()), path, "cannot write the slice thickness");
  check(measures.setSpacingBetweenSlices(decimal(g.spacing.z()).c_str()), path, "cannot write the slice spacing");
  check(seg.addForAllFrames(measures), path, "cannot write the pixel spacing");
  const std::string dimensions = newUid();
  IODMultiframeDimensionModule& dims = seg.getDimensions();
  check(dims.addDimensionIndex(DCM_ReferencedSegmentNumber, dimensions.c_str(), DCM_SegmentIdentificationSequence,
                               "Segment"),
        path, "cannot write the dimensions");
  check(dims.addDimensionIndex(DCM_ImagePositionPatient, dimensions.c_str(), DCM_PlanePositionSequence, "Slice"),
        path, "cannot write the dimensions");
}

void addSegments(DcmSegmentation& seg, const LabelTable& table, const std::vector<Label>& ids,
                 const std::string& path) {
  for (Label id : ids) {
    const LabelEntry* entry = table.find(id);
    const std::string name = entry ? entry->name : "label_" + std::to_string(id);
    const std::array<std::uint8_t, 3> rgb = entry ? entry->color : defaultLabelColor(id);
    DcmSegment* raw = nullptr;
    check(DcmSegment::create(raw, name.substr(0, 64).c_str(), kTissue, kTissue, DcmSegTypes::SAT_AUTOMATIC, "Vesalius"),
          path, "cannot write segment '" + name + "'");
    std::unique_ptr<DcmSegment> segment(raw);
    check(segment->setSegmentDescription(labelDescription(id).c_str()), path, "cannot write a segment");
    double l = 0, a = 0, b = 0;
    IODCIELabUtil::rgb2DicomLab(l, a, b, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
    check(segment->setRecommendedDisplayCIELabValue(Uint16(std::lround(l)), Uint16(std::lround(a)),
                                                    Uint16(std::lround(b))),
          path, "cannot write the colour of '" + name + "'");
    Uint16 number = 0;
    check(seg.addSegment(segment.get(), number), path, "cannot add segment '" + name + "'");
    segment.release();  // the segmentation owns it now
  }
}

// The frames in the order they were added: the label and slice each one shows.
using FrameList = std::vector<std::pair<Label, int>>;

void addFrame(DcmSegmentation& seg, const Grid<Label>& labels, Label id, Uint16 segmentNumber, int k,
              const DicomSourceSeries* source, const std::string& path, FrameList& added) {
  const GridGeometry& g = labels.geometry;
  const std::size_t sliceSize = std::size_t(g.size.x()) * g.size.y();
  std::vector<Uint8> mask(sliceSize);
  const Label* slice = labels.values.data() + k * sliceSize;
  for (std::size_t n = 0; n < sliceSize; ++n) mask[n] = slice[n] == id && id != 0;
  const Eigen::Vector3d p = g.indexToWorld(Eigen::Vector3d(0, 0, k));
  std::unique_ptr<FGPlanePosPatient> position(
      FGPlanePosPatient::createMinimal(decimal(p.x()).c_str(), decimal(p.y()).c_str(), decimal(p.z()).c_str()));
  FGFrameContent content;
  check(content.setDimensionIndexValues(segmentNumber, 0), path, "cannot write frame content");
  check(content.setDimensionIndexValues(Uint32(k + 1), 1), path, "cannot write frame content");
  OFVector<FGBase*> groups;
  groups.push_back(position.get());
  groups.push_back(&content);
  std::unique_ptr<FGDerivationImage> derivation;
  if (const DicomSourceImage* image = sourceImageAt(source, g, k)) {
    ImageSOPInstanceReferenceMacro reference;
    check(reference.setReferencedSOPClassUID(image->sopClassUid.c_str()), path, "cannot refer to a source image");
    check(reference.setReferencedSOPInstanceUID(image->sopInstanceUid.c_str()), path, "cannot refer to a source image");
    OFVector<ImageSOPInstanceReferenceMacro> references;
    references.push_back(reference);
    derivation.reset(DcmSegmentation::createDerivationImageFG(references, "Segmented by Vesalius"));
    if (!derivation) throw BadInput(path, "cannot refer to source image " + image->sopInstanceUid);
    groups.push_back(derivation.get());
  }
  check(seg.addFrame(mask.data(), segmentNumber, groups), path, "cannot add a frame");
  added.emplace_back(id, k);
}

// Pixel Data packed by us: frames follow each other bit by bit (PS3.5 8.1.1, Bits Allocated 1), least
// significant bit first, padded to an even length. DCMTK 3.6.7 packs a frame wrong when the frame before it
// does not end on a byte boundary (rows·columns not a multiple of 8).
void putPixelData(DcmItem& dataset, const Grid<Label>& labels, const FrameList& frames, const std::string& path) {
  const GridGeometry& g = labels.geometry;
  const std::size_t sliceSize = std::size_t(g.size.x()) * g.size.y();
  std::vector<Uint8> bits((frames.size() * sliceSize + 7) / 8 + 1, 0);
  bits.resize(bits.size() / 2 * 2);
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto [id, k] = frames[f];
    const Label* slice = labels.values.data() + k * sliceSize;
    for (std::size_t n = 0; n < sliceSize; ++n)
      if (id != 0 && slice[n] == id) {
        const std::size_t bit = f * sliceSize + n;
        bits[bit / 8] |= Uint8(1u << (bit % 8));
      }
  }
  check(dataset.putAndInsertUint8Array(DCM_PixelData, bits.data(), bits.size()), path, "cannot write the pixels");
}

void addReferencedSeries(DcmSegmentation& seg, const DicomSourceSeries& source, const std::string& path) {
  if (source.seriesInstanceUid.empty()) return;
  auto* item = new IODSeriesAndInstanceReferenceMacro::ReferencedSeriesItem;
  seg.getCommonInstanceReference().getReferencedSeriesItems().push_back(item);
  check(item->setSeriesInstanceUID(source.seriesInstanceUid.c_str()), path, "cannot refer to the source series");
  for (const DicomSourceImage& image : source.images)
    if (!image.sopClassUid.empty() && !image.sopInstanceUid.empty())
      check(item->addReference(image.sopClassUid.c_str(), image.sopInstanceUid.c_str()), path,
            "cannot refer to source image " + image.sopInstanceUid);
}

void writeSegFile(const std::string& path, const std::string& reportedPath, const LabelMap& labelMap,
                  const DicomSourceSeries* source) {
  quietDcmtk();
  const Grid<Label>& labels = labelMap.labels;
  const GridGeometry& g = labels.geometry;
  checkGrid(g, reportedPath);
  const SliceFrames frames = framesOf(labels);
  if (frames.ids.empty())
    throw BadInput(reportedPath, "the label map holds no labels; a DICOM segmentation needs at least one segment");
  DcmSegmentation* raw = nullptr;
  const IODGeneralEquipmentModule::EquipmentInfo equipment("Vesalius", "Vesalius", "1", VESALIUS_VERSION);
  const ContentIdentificationMacro content("1", "SEGMENTATION", "Label map", "Vesalius");
  check(DcmSegmentation::createBinarySegmentation(raw, Uint16(g.size.y()), Uint16(g.size.x()), equipment, content),
        reportedPath, "cannot make a DICOM segmentation");
  std::unique_ptr<DcmSegmentation> seg(raw);
  check(seg->getSeries().setSeriesDescription("Vesalius label map"), reportedPath, "cannot set the series");
  check(seg->getSeries().setSeriesNumber("1000"), reportedPath, "cannot set the series");
  if (source) setSourceModules(*seg, *source, reportedPath);
  if (!source || source->frameOfReferenceUid.empty())
    check(seg->getFrameOfReference().setFrameOfReferenceUID(newUid().c_str()), reportedPath,
          "cannot set the frame of reference");
  addSharedGeometry(*seg, g, reportedPath);
  addSegments(*seg, labelMap.table, frames.ids, reportedPath);
  // The frames span the grid's first and last slices, so a reader finds the whole grid.
  bool first = false, last = false;
  for (const std::vector<int>& slices : frames.slicesOfSegment)
    first |= slices.front() == 0, last |= slices.back() == g.size.z() - 1;
  FrameList added;
  if (!first) addFrame(*seg, labels, 0, 1, 0, source, reportedPath, added);
  for (std::size_t s = 0; s < frames.ids.size(); ++s)
    for (int k : frames.slicesOfSegment[s])
      addFrame(*seg, labels, frames.ids[s], Uint16(s + 1), k, source, reportedPath, added);
  if (!last && g.size.z() > 1) addFrame(*seg, labels, 0, 1, g.size.z() - 1, source, reportedPath, added);
  if (source) addReferencedSeries(*seg, *source, reportedPath);
  DcmFileFormat file;
  check(seg->writeDataset(*file.getDataset()), reportedPath, "cannot make the DICOM segmentation");
  putPixelData(*file.getDataset(), labels, added, reportedPath);
  saveWhole(file, EXS_LittleEndianExplicit, path, reportedPath, "DICOM segmentation");
}

// ---------------------------------------------------------------------------------------------- reading

struct Frame {
  Eigen::Vector3d position;
  Uint16 segmentNumber = 0;
  std::vector<std::string> sourceInstances;  // SOP Instance UIDs the frame was derived from
};

template <class G>
G* group(FGInterface& groups, std::size_t frame, DcmFGTypes::E_FGType type) {
  return dynamic_cast<G*>(groups.get(Uint32(frame), type));
}

std::vector<Frame> readFrames(DcmSegmentation& seg, const std::string& path, Eigen::Vector3d& row,
                              Eigen::Vector3d& column, Eigen::Vector2d& pixelSpacing, double& sliceSpacing) {
  FGInterface& groups = seg.getFunctionalGroups();
  const std::size_t count = seg.getNumberOfFrames();
  if (count == 0) throw BadInput(path, "the DICOM segmentation holds no frames");
  std::vector<Frame> frames(count);
  for (std::size_t f = 0; f < count; ++f) {
    auto* orientation = group<FGPlaneOrientationPatient>(groups, f, DcmFGTypes::EFG_PLANEORIENTPATIENT);
    auto* position = group<FGPlanePosPatient>(groups, f, DcmFGTypes::EFG_PLANEPOSPATIENT);
    auto* measures = group<FGPixelMeasures>(groups, f, DcmFGTypes::EFG_PIXELMEASURES);
    auto* segment = group<FGSegmentation>(groups, f, DcmFGTypes::EFG_SEGMENTATION);
    if (!orientation || !position || !measures || !segment)
      throw BadInput(path, "frame " + std::to_string(f + 1) +
                               " lacks its plane orientation, plane position, pixel measures or segment number");
    Eigen::Matrix<double, 6, 1> cosines;
    Float64 v[6];
    if (orientation->getImageOrientationPatient(v[0], v[1], v[2], v[3], v[4], v[5]).bad())
      throw BadInput(path, "frame " + std::to_string(f + 1) + ": no Image Orientation (Patient)");
    for (int c = 0; c < 6; ++c) cosines[c] = v[c];
    const Eigen::Vector3d r = cosines.head<3>(), c = cosines.tail<3>();
    if (f == 0) row = r, column = c;
    else if ((r - row).norm() > 1e-4 || (c - column).norm() > 1e-4)
      throw BadInput(path, "frames differ in orientation; a label map needs one");
    Float64 x = 0, y = 0, z = 0;
    if (position->getImagePositionPatient(x, y, z).bad())
      throw BadInput(path, "frame " + std::to_string(f + 1) + ": no Image Position (Patient)");
    frames[f].position = {x, y, z};
    Float64 between = 0, along = 0, spacing = 0, thickness = 0;
    if (measures->getPixelSpacing(between, 0).bad() || measures->getPixelSpacing(along, 1).bad())
      throw BadInput(path, "frame " + std::to_string(f + 1) + ": no Pixel Spacing");
    pixelSpacing = {along, between};  // i (along a row), j (between rows)
    if (measures->getSpacingBetweenSlices(spacing).good() && spacing > 0) sliceSpacing = spacing;
    else if (measures->getSliceThickness(thickness).good() && thickness > 0 && sliceSpacing <= 0)
      sliceSpacing = thickness;
    if (segment->getReferencedSegmentNumber(frames[f].segmentNumber).bad())
      throw BadInput(path, "frame " + std::to_string(f + 1) + ": no Referenced Segment Number");
    if (auto* derivation = group<FGDerivationImage>(groups, f, DcmFGTypes::EFG_DERIVATIONIMAGE))
      for (DerivationImageItem* item : derivation->getDerivationImageItems())
        for (SourceImageItem* sourceItem : item->getSourceImageItems()) {
          OFString uid;
          if (sourceItem->getImageSOPInstanceReference().getReferencedSOPInstanceUID(uid).good())
            frames[f].sourceInstances.push_back(uid.c_str());
        }
  }
  return frames;
}

// The grid the frames lie on, and each frame's slice. Slices run along the normal from the lowest frame.
GridGeometry gridOf(std::vector<Frame>& frames, std::vector<int>& sliceOf, const Eigen::Vector3d& row,
                    const Eigen::Vector3d& column, const Eigen::Vector2d& pixelSpacing, double sliceSpacing,
                    int rows, int columns, const std::string& path) {
  const Eigen::Vector3d normal = row.cross(column).normalized();
  std::vector<double> along(frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) along[f] = normal.dot(frames[f].position);
  const auto [low, high] = std::minmax_element(along.begin(), along.end());
  const Eigen::Vector3d first = frames[low - along.begin()].position, lastPosition = frames[high - along.begin()].position;
  const double extent = *high - *low;
  if (!(sliceSpacing > 0)) {
    // No spacing given: the smallest gap between distinct slice positions.
    std::vector<double> sorted = along;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t n = 1; n < sorted.size(); ++n)
      if (sorted[n] - sorted[n - 1] > 1e-3 && (!(sliceSpacing > 0) || sorted[n] - sorted[n - 1] < sliceSpacing))
        sliceSpacing = sorted[n] - sorted[n - 1];
    if (!(sliceSpacing > 0)) sliceSpacing = 1;
  }
  const int slices = int(std::lround(extent / sliceSpacing)) + 1;
  // The step between slices from the end frames, so a tilted stack keeps its shear.
  const Eigen::Vector3d step = slices > 1 ? Eigen::Vector3d((lastPosition - first) / (slices - 1))
                                          : Eigen::Vector3d(normal * sliceSpacing);
  GridGeometry g;
  g.size = {columns, rows, slices};
  g.origin = first;
  g.spacing = {pixelSpacing.x(), pixelSpacing.y(), step.norm()};
  g.direction.col(0) = row.normalized();
  g.direction.col(1) = column.normalized();
  g.direction.col(2) = step.normalized();
  const double tolerance = 1e-3 + 1e-3 * g.spacing.z();
  sliceOf.resize(frames.size());
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const int k = int(std::lround((along[f] - *low) / normal.dot(step)));
    if ((frames[f].position - (first + k * step)).norm() > tolerance)
      throw BadInput(path, "frame " + std::to_string(f + 1) + " does not lie on the grid of the other frames");
    sliceOf[f] = k;
  }
  g.validate(path);
  return g;
}

std::array<std::uint8_t, 3> rgbOf(DcmSegment& segment, Label id) {
  Uint16 l = 0, a = 0, b = 0;
  if (segment.getRecommendedDisplayCIELabValue(l, a, b).bad()) return defaultLabelColor(id);
  double r = 0, g = 0, bl = 0;
  IODCIELabUtil::dicomLab2RGB(r, g, bl, l, a, b);
  auto byte = [](double v) { return std::uint8_t(std::clamp(std::lround(v * 255), 0L, 255L)); };
  return {{byte(r), byte(g), byte(bl)}};
}

// Ids by segment number: "label <id>" descriptions when every segment has a distinct one, else the numbers.
std::map<Uint16, LabelEntry> segmentEntries(DcmSegmentation& seg, const std::string& path) {
  const std::size_t count = seg.getNumberOfSegments();
  if (count == 0) throw BadInput(path, "the DICOM segmentation holds no segments");
  if (count > 65535) throw BadInput(path, "more than 65535 segments");
  std::map<Uint16, LabelEntry> entries;
  std::vector<bool> taken(65536, false);
  bool described = true;
  for (std::size_t number = 1; number <= count; ++number) {
    DcmSegment* segment = seg.getSegment(number);
    if (!segment) throw BadInput(path, "segment " + std::to_string(number) + " is missing");
    OFString label, description;
    segment->getSegmentLabel(label);
    segment->getSegmentDescription(description);
    LabelEntry entry{Label(number), label.c_str(), {}};
    const Label id = labelOfDescription(description.c_str());
    if (id != 0 && !taken[id]) taken[id] = true, entry.id = id;
    else described = false;
    if (entry.name.empty()) entry.name = "Segment_" + std::to_string(number);
    entries[Uint16(number)] = entry;
  }
  for (auto& [number, entry] : entries) {
    if (!described) entry.id = number;
    entry.color = rgbOf(*seg.getSegment(number), entry.id);
  }
  return entries;
}

DicomSourceSeries referencesOf(DcmFileFormat& file, const std::vector<Frame>& frames) {
  DcmDataset& data = *file.getDataset();
  DicomSourceSeries source = sourceAttributes(data);
  source.seriesInstanceUid.clear();
  DcmItem* series = nullptr;
  if (data.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series, 0).good() && series) {
    source.seriesInstanceUid = text(*series, DCM_SeriesInstanceUID);
    DcmItem* instance = nullptr;
    for (long n = 0; series->findAndGetSequenceItem(DCM_ReferencedInstanceSequence, instance, n).good() && instance; ++n)
      source.images.push_back({text(*instance, DCM_ReferencedSOPClassUID), text(*instance, DCM_ReferencedSOPInstanceUID), {}});
  }
  for (DicomSourceImage& image : source.images)
    for (const Frame& frame : frames)
      if (std::find(frame.sourceInstances.begin(), frame.sourceInstances.end(), image.sopInstanceUid) !=
          frame.sourceInstances.end())
        image.position = frame.position;
  return source;
}

}  // namespace

bool isDicomSegPath(const std::string& path) {
  return fileExtension(path) == ".dcm" && !isDicomRtStructPath(path);
}

bool isDicomSegFile(const std::string& path) { return isDicomFileOfClass(path, UID_SegmentationStorage); }

std::optional<DicomSourceSeries> readDicomSource(const std::string& path, const std::string& seriesUid) {
  std::error_code error;
  if (fs::is_directory(path, error)) {
    const std::vector<itk_seam::RawDicomSeries> all = itk_seam::findDicomSeries(path);
    if (all.empty()) throw BadInput(path, "no DICOM series in this folder");
    if (seriesUid.empty() && all.size() > 1)
      throw BadInput(path, "holds " + std::to_string(all.size()) + " DICOM series; choose one by its series UID");
    for (const itk_seam::RawDicomSeries& series : all)
      if (series.uid == seriesUid || seriesUid.empty()) return seriesOfFiles(series.files);
    throw UsageError(path + ": no DICOM series with UID " + seriesUid);
  }
  if (fileExtension(path) != ".dcm" && !itk_seam::isDicomFile(path)) return std::nullopt;
  DcmFileFormat file;
  loadDicom(file, path, false);
  if (sopClassOf(file) == UID_SegmentationStorage) return readDicomSeg(path).source;
  return seriesOfFiles({path});
}

void writeDicomSeg(const std::string& path, const LabelMap& labelMap, const DicomSourceSeries* source,
                   const WriteOptions& options) {
  if (std::int64_t(labelMap.labels.values.size()) != labelMap.labels.geometry.voxelCount())
    throw std::invalid_argument(path + ": label values do not fill the grid");
  writeAtomically(path, options, [&](const std::string& temporaryPath) {
    writeSegFile(temporaryPath, path, labelMap, source);
  });
}

DicomSegmentation readDicomSeg(const std::string& path) {
  DcmFileFormat file;
  loadDicom(file, path, true);
  const std::string sopClass = sopClassOf(file);
  if (sopClass == UID_RTStructureSetStorage)
    throw BadInput(path, "an RT Structure Set, not a DICOM segmentation: its contours have no grid of their own and "
                         "are read onto a scan's grid (io/dicom_rtstruct.h)");
  if (sopClass != UID_SegmentationStorage)
    throw BadInput(path, "not a DICOM segmentation (SOP Class UID " + (sopClass.empty() ? "missing" : sopClass) + ")");
  // The frames' bits follow each other without padding (PS3.5 8.1.1, Bits Allocated 1): frame f's pixel n
  // is bit f·rows·columns + n, least significant first. Copied before DCMTK reads the dataset, and read
  // here: DCMTK 3.6.7 unpacks a frame wrong when the frame before it does not end on a byte boundary.
  const Uint8* pixelData = nullptr;
  unsigned long byteCount = 0;
  if (file.getDataset()->findAndGetUint8Array(DCM_PixelData, pixelData, &byteCount).bad() || !pixelData)
    throw BadInput(path, "no Pixel Data that is not compressed");
  const std::vector<Uint8> bits(pixelData, pixelData + byteCount);
  DcmSegmentation* raw = nullptr;
  check(DcmSegmentation::loadDataset(*file.getDataset(), raw), path, "cannot read the DICOM segmentation");
  std::unique_ptr<DcmSegmentation> seg(raw);
  if (seg->getSegmentationType() != DcmSegTypes::ST_BINARY)
    throw BadInput(path, "a fractional DICOM segmentation; only binary ones are read as label maps");
  Uint16 rows = 0, columns = 0;
  file.getDataset()->findAndGetUint16(DCM_Rows, rows);
  file.getDataset()->findAndGetUint16(DCM_Columns, columns);
  if (rows == 0 || columns == 0) throw BadInput(path, "no Rows or Columns");
  Eigen::Vector3d row, column;
  Eigen::Vector2d pixelSpacing;
  double sliceSpacing = 0;
  std::vector<Frame> frames = readFrames(*seg, path, row, column, pixelSpacing, sliceSpacing);
  std::vector<int> sliceOf;
  DicomSegmentation result;
  LabelMap& map = result.labelMap;
  map.labels = Grid<Label>(gridOf(frames, sliceOf, row, column, pixelSpacing, sliceSpacing, rows, columns, path));
  const std::map<Uint16, LabelEntry> entries = segmentEntries(*seg, path);
  for (const auto& [number, entry] : entries) map.table.add(entry);
  const std::size_t sliceSize = std::size_t(rows) * columns;
  if (byteCount * 8 < frames.size() * sliceSize)
    throw BadInput(path, "Pixel Data holds " + std::to_string(byteCount) + " bytes, fewer than " +
                             std::to_string(frames.size()) + " frames need");
  std::map<std::pair<Label, Label>, std::int64_t> overlaps;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto entry = entries.find(frames[f].segmentNumber);
    if (entry == entries.end())
      throw BadInput(path, "frame " + std::to_string(f + 1) + " refers to segment " +
                               std::to_string(frames[f].segmentNumber) + ", which the file does not list");
    Label* slice = map.labels.values.data() + sliceOf[f] * sliceSize;
    const Label id = entry->second.id;
    for (std::size_t n = 0; n < sliceSize; ++n) {
      const std::size_t bit = f * sliceSize + n;
      if (!((bits[bit / 8] >> (bit % 8)) & 1)) continue;
      if (slice[n] != 0 && slice[n] != id) ++overlaps[{std::min(slice[n], id), std::max(slice[n], id)}];
      else slice[n] = id;
    }
  }
  if (!overlaps.empty()) {
    std::string pairs;
    for (const auto& [pair, voxels] : overlaps)
      pairs += (pairs.empty() ? "" : ", ") + std::string("'") + map.table.find(pair.first)->name + "' and '" +
               map.table.find(pair.second)->name + "' share " + std::to_string(voxels) + " voxels";
    throw BadInput(path, "segments overlap, which a label map cannot hold: " + pairs);
  }
  DicomSourceSeries source = referencesOf(file, frames);
  if (!source.seriesInstanceUid.empty() || !source.images.empty()) result.source = std::move(source);
  return result;
}

}  // namespace vesalius::io
