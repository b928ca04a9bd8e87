// --labels (or --organs) as every command that reads a label map takes it, with --grid beside it: a DICOM
// RT Structure Set holds contours in patient space and no grid of its own (io/dicom_rtstruct.h), so it is
// read onto the grid of the scan --grid names.
#pragma once

#include "common.h"

#include "vesalius/core/label_map.h"
#include "vesalius/io/report.h"

#include <string>

namespace vesalius::cli {

// What --labels may be, for a command that takes any label map.
constexpr const char* kLabelsHelp =
    "Label map (NIfTI, NRRD, MetaImage, .seg.nrrd, DICOM SEG), or an RT Structure Set (.rtstruct.dcm) with --grid";

// Adds the label map option `name` (--labels, --organs; with `description`) and --grid to `command`;
// returns the label map option, for ->required().
CLI::Option* addLabelsOption(CLI::App& command, std::string& labels, std::string& grid, const std::string& description,
                             const std::string& name = "--labels");

// The label map at `labels` (io::readLabelMap, with `table` if given). An RT Structure Set (a path ending
// .rtstruct.dcm, or a file of that SOP class under any name, io::isDicomRtStructFile) is read onto the grid
// of the scan at `grid` with `table` (io::readDicomRtStructOntoScan: the same table rule as a DICOM SEG's,
// and a DICOM scan of another frame of reference refused); `grid` goes into `report` as an input.
// UsageError for an RT Structure Set without `grid`, and for `grid` with any other label map, whose grid is
// its own (it is not resampled).
LabelMap readLabelsOption(const std::string& labels, const std::string& table, const std::string& grid,
                          io::Report& report);

}  // namespace vesalius::cli
