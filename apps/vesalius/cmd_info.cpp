// vesalius info: what a scan, label table, mesh, marker, motion or skeleton file holds.
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/dicom_series.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/label_table_io.h"
#include "vesalius/io/marker_io.h"
#include "vesalius/io/mesh_io.h"
#include "vesalius/io/motion_io.h"
#include "vesalius/io/skeleton_io.h"
#include "vesalius/io/slicer_segmentation.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace vesalius::cli {

namespace {

namespace fs = std::filesystem;

struct InfoOptions {
  std::string file, series, scan, baseMesh;
};

std::string vec(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << std::setprecision(6) << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

void printScan(const InfoOptions& o) {
  if (fs::is_directory(o.file) && o.series.empty()) {
    const auto series = io::listDicomSeries(o.file);
    if (series.size() > 1) {
      std::cout << o.file << ": DICOM folder with " << series.size() << " series (choose one with --series)\n";
      for (const auto& s : series)
        std::cout << "  " << s.uid << "  " << s.modality << "  " << s.sliceCount << " slices  " << s.description << '\n';
      return;
    }
  }
  const io::ScanInfo info = io::describeScan(o.file, io::ScanReadOptions{o.series});
  const GridGeometry& g = info.geometry;
  std::cout << o.file << ": scan (" << info.format << ")\n"
            << "  size         " << g.size.x() << " x " << g.size.y() << " x " << g.size.z() << " voxels\n"
            << "  spacing      " << g.spacing.x() << " x " << g.spacing.y() << " x " << g.spacing.z() << " mm\n"
            << "  origin       " << vec(g.origin) << " mm, LPS\n"
            << "  direction    " << vec(g.direction.col(0)) << " " << vec(g.direction.col(1)) << " "
            << vec(g.direction.col(2)) << "\n"
            << "  orientation  " << info.orientation << "\n"
            << "  pixel type   " << pixelTypeName(info.pixelType) << ", " << info.components << " component(s)\n";
  if (info.valueRange)
    std::cout << "  values       " << info.valueRange->minimum << " .. " << info.valueRange->maximum << '\n';
}

void printMarkers(const InfoOptions& o) {
  std::optional<GridGeometry> geometry;
  if (!o.scan.empty()) geometry = io::describeScan(o.scan).geometry;
  const MarkerSet set = io::readMarkers(o.file, io::MarkerReadOptions{MarkerKind::Landmark, geometry ? &*geometry : nullptr});
  std::size_t undefined = 0, preview = 0, missing = 0;
  for (const Marker& m : set.markers) {
    undefined += m.status == MarkerStatus::Undefined;
    preview += m.status == MarkerStatus::Preview;
    missing += m.status == MarkerStatus::Missing;
  }
  std::cout << o.file << ": markers" << (set.name.empty() ? "" : " '" + set.name + "'") << "\n"
            << "  landmarks    " << set.count(MarkerKind::Landmark) << "\n"
            << "  ICP markers  " << set.count(MarkerKind::IcpMarker) << "\n"
            << "  attachments  " << set.count(MarkerKind::Attachment) << "\n"
            << "  status       " << set.countDefined() << " defined, " << undefined << " undefined, " << preview
            << " preview, " << missing << " missing\n"
            << "  coordinates  LPS mm (as read; RAS files are converted)\n";
}

void printMesh(const InfoOptions& o, io::MeshKind kind) {
  // Read before printing anything, so a bad file gives its one error line and nothing else.
  const std::string text = kind == io::MeshKind::kSurface ? io::describe(io::summarize(io::readTriMesh(o.file)))
                                                          : io::describe(io::summarize(io::readTetMesh(o.file)));
  std::cout << o.file << (kind == io::MeshKind::kSurface ? ": surface mesh\n" : ": tetrahedral mesh\n") << text
            << '\n';
}

void printMotion(const InfoOptions& o) {
  const Motion motion = io::readBvh(o.file, std::cerr);
  const double rate = 1.0 / motion.frameTime;
  std::cout << o.file << ": motion (BVH)\n"
            << "  joints       " << motion.skeleton.joints.size() << " (root '"
            << (motion.skeleton.joints.empty() ? "" : motion.skeleton.joints[0].name) << "')\n"
            << "  channels     " << motion.values.cols() << "\n"
            << "  frames       " << motion.frameCount() << " at " << rate << " Hz ("
            << motion.frameCount() * motion.frameTime << " s)\n";
}

void printOpenSim(const InfoOptions& o) {
  const MusculoskeletalModel model = io::readOpenSimModel(o.file);
  std::size_t points = 0;
  for (const Muscle& m : model.muscles) points += m.path.size();
  std::cout << o.file << ": OpenSim model '" << model.name << "' (lengths in metres)\n"
            << "  bodies       " << model.bodies.joints.size() << "\n"
            << "  meshes       " << model.geometry.size() << "\n"
            << "  muscles      " << model.muscles.size() << " with " << points << " path points\n";
}

void printMakeHuman(const InfoOptions& o) {
  const std::string base = o.baseMesh.empty() ? (fs::path(o.file).parent_path() / "base.obj").string() : o.baseMesh;
  if (!fs::exists(base)) throw UsageError(o.file + ": a MakeHuman skeleton needs its base mesh; pass --base-mesh");
  const Skeleton skeleton = io::readMakeHumanSkeleton(o.file, io::readTriMesh(base).V);
  int roots = 0;
  for (const Joint& j : skeleton.joints) roots += j.parent < 0;
  std::cout << o.file << ": MakeHuman skeleton (decimetres, +Y up)\n"
            << "  bones        " << skeleton.joints.size() << " (" << roots << " root)\n";
}

void printLabelTable(const InfoOptions& o) {
  const LabelTable table = io::readLabelTable(o.file);
  std::cout << o.file << ": label table, " << table.entries.size() << " labels\n";
  for (const LabelEntry& e : table.entries) std::cout << "  " << std::setw(5) << e.id << "  " << e.name << '\n';
}

void printSegmentation(const InfoOptions& o) {
  const io::SlicerSegmentation seg = io::readSlicerSegmentation(o.file);
  const GridGeometry& g = seg.layers.front().geometry;
  std::cout << o.file << ": 3D Slicer segmentation, " << seg.segments.size() << " segments in " << seg.layers.size()
            << (seg.layers.size() == 1 ? " layer\n" : " layers\n")
            << "  size         " << g.size.x() << " x " << g.size.y() << " x " << g.size.z() << " voxels\n"
            << "  spacing      " << g.spacing.x() << " x " << g.spacing.y() << " x " << g.spacing.z() << " mm\n"
            << "  origin       " << vec(g.origin) << " mm, LPS\n"
            << "  layer  value     voxels  colour       name\n";
  for (const io::SlicerSegment& s : seg.segments) {
    const std::vector<Label>& values = seg.layers[std::size_t(s.layer)].values;
    const auto voxels = std::count(values.begin(), values.end(), s.labelValue);
    char line[96];
    std::snprintf(line, sizeof line, "  %5d  %5u  %9lld  %3u %3u %3u  ", s.layer, unsigned(s.labelValue),
                  (long long)voxels, unsigned(s.color[0]), unsigned(s.color[1]), unsigned(s.color[2]));
    std::cout << line << s.name << '\n';
  }
  for (const io::SegmentOverlap& overlap : io::segmentOverlaps(seg))
    std::cout << "  overlap      '" << seg.segments[overlap.first].name << "' and '"
              << seg.segments[overlap.second].name << "' share " << overlap.voxels << " voxels\n";
}

void printDicomSeg(const InfoOptions& o) {
  const io::DicomSegmentation seg = io::readDicomSeg(o.file);
  const GridGeometry& g = seg.labelMap.labels.geometry;
  std::cout << o.file << ": DICOM segmentation, " << seg.labelMap.table.entries.size() << " segments\n"
            << "  size         " << g.size.x() << " x " << g.size.y() << " x " << g.size.z() << " voxels\n"
            << "  spacing      " << g.spacing.x() << " x " << g.spacing.y() << " x " << g.spacing.z() << " mm\n"
            << "  origin       " << vec(g.origin) << " mm, LPS\n";
  if (seg.source)
    std::cout << "  refers to    series " << seg.source->seriesInstanceUid << " (" << seg.source->images.size()
              << " images) of study " << seg.source->studyInstanceUid << '\n';
  std::cout << "     id     voxels  colour       name\n";
  const std::vector<Label>& values = seg.labelMap.labels.values;
  for (const LabelEntry& e : seg.labelMap.table.entries) {
    char line[96];
    std::snprintf(line, sizeof line, "  %5u  %9lld  %3u %3u %3u  ", unsigned(e.id),
                  (long long)std::count(values.begin(), values.end(), e.id), unsigned(e.color[0]),
                  unsigned(e.color[1]), unsigned(e.color[2]));
    std::cout << line << e.name << '\n';
  }
}

void runInfo(const InfoOptions& o) {
  if (!fs::exists(o.file)) throw BadInput(o.file, "no such file or folder");
  const std::string ext = fileExtension(o.file);
  if (ext == ".seg.nrrd")
    printSegmentation(o);
  else if (ext == ".dcm" && io::isDicomSegFile(o.file))
    printDicomSeg(o);
  else if (fs::is_directory(o.file) || ext == ".nii" || ext == ".nii.gz" || ext == ".nrrd" || ext == ".nhdr" ||
      ext == ".mha" || ext == ".mhd" || ext == ".dcm")
    printScan(o);
  else if (io::isLabelTableFile(o.file))  // before markers: a Slicer colour table may be a .csv
    printLabelTable(o);
  else if (io::isMarkerFile(o.file))
    printMarkers(o);
  else if (auto kind = io::meshFileKind(o.file))
    printMesh(o, *kind);
  else if (ext == ".bvh")
    printMotion(o);
  else if (ext == ".osim")
    printOpenSim(o);
  else if (ext == ".mhskel")
    printMakeHuman(o);
  else
    throw BadInput(o.file, "unknown file type '" + ext + "'");
}

}  // namespace

void addInfoCommand(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Describe a scan, segmentation, mesh, marker, motion, skeleton or label-table file");
  cmd->add_option("file", o->file, "File, or DICOM folder")->required();
  cmd->add_option("--series", o->series, "DICOM series UID, for a folder holding several");
  cmd->add_option("--scan", o->scan, "Scan an ITK-SNAP .annot file was made on (for its voxel geometry)");
  cmd->add_option("--base-mesh", o->baseMesh, "MakeHuman base.obj for a .mhskel (default: beside it)");
  cmd->footer("Examples:\n  vesalius info testdata/head-mri/ch2.nii.gz\n  vesalius info testdata/liver/liver.msh\n"
              "  vesalius info testdata/dicom/ct-series-jpeg2000");
  cmd->callback([o] { runInfo(*o); });
}

}  // namespace vesalius::cli
