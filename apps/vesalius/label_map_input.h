// --labels as every command that reads a label map takes it, with --grid beside it: a DICOM RT Structure
// Set holds contours in patient space and no grid of its own (io/dicom_rtstruct.h), so it is read onto
// the grid of the scan --grid names.
#pragma once

#include "common.h"

#include "vesalius/core/label_map.h"
#include "vesalius/io/report.h"

#include <string>

namespace vesalius::cli {

// What --labels may be, for a command that takes any label map.
constexpr const char* kLabelsHelp =
    "Label map (NIfTI, NRRD, MetaImage, .seg.nrrd, DICOM SEG), or an RT Structure Set (.rtstruct.dcm) with --grid";

// Adds --labels (with `description`) and --grid to `command`; returns --labels, for ->required().
CLI::Option* addLabelsOption(CLI::App& command, std::string& labels, std::string& grid,
                             const std::string& description);

// The label map at `labels` (io::readLabelMap, with `table` if given). An RT Structure Set (a path ending
// .rtstruct.dcm, or a .dcm file of that SOP class) is read onto the grid of the scan at `grid` (any scan
// io::describeScan reads), an explicit `table`'s entries taking the place of the ROIs' names and colours;
// `grid` goes into `report` as an input. UsageError for an RT Structure Set without `grid`, and for
// `grid` with any other label map, whose grid is its own (it is not resampled).
LabelMap readLabelsOption(const std::string& labels, const std::string& table, const std::string& grid,
                          io::Report& report);

}  // namespace vesalius::cli
