// What `vesalius labels` writes (docs/cli.md): the edited label map with its table beside it, and the
// summary of what changed (voxels and millilitres before and after, per row) printed and in the report.
#pragma once

#include "common.h"

#include "vesalius/core/label_map.h"
#include "vesalius/io/report.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vesalius::cli {

// The map a `labels` action edits, read from `path` (onto the scan `grid` if it is an RT Structure Set),
// its voxels per id, and the labels the user names: resolved, checked and named as the summary rows and
// the messages name them.
struct LabelsInput {
  std::string path, grid;
  LabelMap map;
  std::vector<std::int64_t> voxels;  // by id: 65536 counts

  LabelsInput(std::string labelsPath, std::string gridPath, LabelMap labelMap);
  // "liver (5)", or "5" for an id without a table entry.
  std::string name(Label id) const;
  // An id or name that must have voxels (BadInput naming `path` otherwise): editing a label the map does
  // not hold is a mistake.
  Label label(const std::string& idOrName) const;
  // The same for each; UsageError if one is given twice.
  std::vector<Label> labels(const std::vector<std::string>& idsOrNames) const;
  // The ids with voxels, but not those of `ids`.
  std::vector<Label> presentExcept(const std::vector<Label>& ids) const;
};

// A summary line: the voxels of ids `before` in the input against those of ids `after` in the output.
struct SummaryRow {
  std::string name;
  std::vector<Label> before, after;
};

constexpr const char* kOutHelp =
    "Label map to write (.nii.gz, .nrrd, .mha) with label tables beside it; or a 3D Slicer segmentation "
    "(.seg.nrrd); or a DICOM segmentation for PACS (.dcm); or an RT Structure Set for radiotherapy planning "
    "(.rtstruct.dcm)";
constexpr const char* kDicomSeriesHelp =
    "DICOM folder of the scan the labels belong to (one series), which a .dcm or .rtstruct.dcm --out refers to; by default a "
    "DICOM segmentation given as --labels passes on the series it refers to, and a DICOM --grid its own";

// Refuses (UsageError) --dicom-series unless --out is a DICOM segmentation (.dcm) or RT Structure Set
// (.rtstruct.dcm).
void checkDicomSeriesOption(const std::string& dicomSeries, const std::string& out);

// Refuses (UsageError) an --out whose map or table is the input map (`labels`) or the table it is read
// with (`table`, empty: the one beside the map).
void refuseInputsAsOutputs(const std::string& labels, const std::string& table, const std::string& out);

// Writes `edited` to `out` with its tables beside it (a .seg.nrrd or .dcm carries its own); a .dcm (DICOM
// SEG, or an RT Structure Set for .rtstruct.dcm, io/dicom_rtstruct.h) refers to the DICOM series in
// `dicomSeries`, else to the one a DICOM SEG input refers to (io/dicom_seg.h), else to the --grid an RT
// Structure Set input was read onto when that is DICOM. Prints each row's voxels and mL in the input
// and in `edited` and puts them in the report, says when the grid changed and prints the paths written.
void writeLabelsOutputs(const LabelsInput& input, const LabelMap& edited, const std::vector<SummaryRow>& rows,
                        const std::string& out, const std::string& dicomSeries, const CommonOptions& common,
                        io::Report& report);

}  // namespace vesalius::cli
