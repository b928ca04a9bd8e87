#include "label_map_input.h"

#include "vesalius/core/error.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/image_io.h"

namespace vesalius::cli {

namespace {

// By name, else by content: a structure set from a planning system or PACS is rarely named for its SOP
// class, and often has no extension at all.
bool isRtStruct(const std::string& path) { return io::isDicomRtStructPath(path) || io::isDicomRtStructFile(path); }

}  // namespace

CLI::Option* addLabelsOption(CLI::App& command, std::string& labels, std::string& grid, const std::string& description,
                             const std::string& name) {
  CLI::Option* option = command.add_option(name, labels, description);
  slicerParameter(command.add_option("--grid", grid,
                                     "Scan whose grid an RT Structure Set given as " + name +
                                         " is read onto (NIfTI, NRRD, MetaImage, DICOM folder of the structure "
                                         "set's frame of reference); only for an RT Structure Set"),
                  SlicerKind::Image, false)
      ->needs(option);
  return option;
}

LabelMap readLabelsOption(const std::string& labels, const std::string& table, const std::string& grid,
                          io::Report& report) {
  const bool rtStruct = isRtStruct(labels);
  if (rtStruct && grid.empty())
    throw UsageError(labels + ": an RT Structure Set holds contours and no grid; pass --grid SCAN, the scan to read "
                              "it onto");
  if (!rtStruct && !grid.empty())
    throw UsageError("--grid is the grid an RT Structure Set is read onto; " + labels +
                     " is a label map on a grid of its own (give it without --grid)");
  if (!rtStruct) return io::readLabelMap(labels, table);
  report.input("grid", grid);
  return io::readDicomRtStructOntoScan(labels, grid, table);
}

}  // namespace vesalius::cli
