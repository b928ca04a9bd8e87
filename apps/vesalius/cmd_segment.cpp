// vesalius segment: tissue classes of a scan as a label map with its label table and a slice picture.
#include "command_runner.h"
#include "common.h"
#include "modality_option.h"

#include "vesalius/core/atomic_file.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"
#include "vesalius/viz/slice_overlay.h"

#include <filesystem>
#include <iostream>
#include <optional>

namespace vesalius::cli {

namespace {

struct SegmentOptions {
  std::string scan, modality = "auto", out, png, series;
  double skinThickness = 2.0;
  CommonOptions common;
};

// The PNG beside the label map: "labels.nii.gz" -> "labels.png".
std::string defaultPngPath(const std::string& labels) {
  const std::string ext = fileExtension(labels);
  return labels.substr(0, labels.size() - ext.size()) + ".png";
}

void runSegment(const SegmentOptions& o, CommandRun& run) {
  // The picture's default name comes from --out, so no option check has seen it: checked before the work,
  // not after the label map is written.
  const std::string png = o.png.empty() ? defaultPngPath(o.out) : o.png;
  checkNotAnInput(png);
  if (!o.common.force && std::filesystem::exists(png)) throw UsageError(png + ": exists; pass --force to replace it");
  run.report.input("scan", o.scan);
  run.report.parameter("skin_thickness_mm", o.skinThickness);

  Image scan;
  {
    auto timer = run.report.time("read scan");
    scan = io::readScan(o.scan, io::ScanReadOptions{o.series});
  }
  const segmentation::Modality modality = resolveModality(o.modality, scan);
  run.report.parameter("modality", segmentation::modalityName(modality));
  // A DICOM SEG or RT Structure Set refers to the series it was made from, when the scan is one.
  const bool rtStruct = io::isDicomRtStructPath(o.out);
  const std::optional<io::DicomSourceSeries> source =
      io::isDicomSegPath(o.out) || rtStruct ? io::readDicomSource(o.scan, o.series) : std::nullopt;
  LabelMap labels;
  {
    auto timer = run.report.time("segment");
    labels = segmentation::segmentTissues(scan, modality, o.skinThickness, &run.progress);
  }
  // The labels, their tables and their picture all or none: a picture that fails leaves no labels.
  std::vector<std::string> outputs = io::labelMapFiles(o.out);
  outputs.push_back(png);
  writeFilesAtomically(outputs, o.common.writeOptions(), [&](const std::vector<std::string>& files) {
    if (source && rtStruct) io::writeDicomRtStruct(files.front(), labels, &*source);
    else if (source) io::writeDicomSeg(files.front(), labels, &*source);
    else io::writeLabelMap(files.front(), labels);
    viz::writeSliceOverlayPng(scan, labels, files.back());
  });
  run.report.output("labels", o.out);
  run.report.output("png", png);
  std::cout << "labels: " << o.out << "\npicture: " << png << '\n';
}

}  // namespace

void addSegmentCommand(CLI::App& app) {
  auto o = std::make_shared<SegmentOptions>();
  CLI::App* cmd = app.add_subcommand("segment", "Segment a scan into tissue classes (skin, fat, soft tissue, bone)");
  cmd->add_option("--scan", o->scan, "Scan: NIfTI, NRRD, MetaImage, or a DICOM folder")->required();
  cmd->add_option("--series", o->series, "DICOM series UID when the folder holds several");
  addModalityOption(*cmd, o->modality);
  slicerParameter(cmd->add_option("--out", o->out,
                                  "Label map to write (.nii.gz, .nrrd, .mha), with label tables beside it for "
                                  "Vesalius (.tsv), 3D Slicer (.ctbl) and ITK-SNAP (.label.txt); or a 3D Slicer "
                                  "segmentation (.seg.nrrd); or a DICOM segmentation for PACS (.dcm) or an RT Structure "
                                  "Set for radiotherapy planning (.rtstruct.dcm), which refer to the scan's series "
                                  "when the scan is DICOM")
                      ->required(),
                  SlicerKind::LabelImage, true, ".nrrd,.nii.gz,.mha");
  cmd->add_option("--png", o->png, "Picture of the labels over three slices (default: beside the label map)");
  cmd->add_option("--skin-thickness", o->skinThickness, "Skin shell thickness in mm")->capture_default_str();
  addCommonOptions(*cmd, o->common);
  cmd->footer("Examples:\n  vesalius segment --scan testdata/ct-abdomen-pelvis/example_ct.nii.gz --modality ct "
              "--out labels.nii.gz\n  vesalius segment --scan testdata/head-mri/ch2.nii.gz --modality mri "
              "--out head.nii.gz\n  vesalius segment --scan ct-series/ --modality ct --out labels.seg.dcm");
  cmd->callback([o] { runCommand("segment", o->common, [&](CommandRun& run) { runSegment(*o, run); }); });
}

}  // namespace vesalius::cli
