#include "label_map_input.h"

#include "vesalius/core/error.h"
#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"
#include "vesalius/io/label_table_io.h"

#include <utility>

namespace vesalius::cli {

namespace {

// By name, else by content for any other .dcm: a structure set from a planning system or PACS is rarely
// named for its SOP class. Other files are not opened here (a NIfTI is no DICOM).
bool isRtStruct(const std::string& path) {
  return io::isDicomRtStructPath(path) || (io::isDicomSegPath(path) && io::isDicomRtStructFile(path));
}

}  // namespace

CLI::Option* addLabelsOption(CLI::App& command, std::string& labels, std::string& grid,
                             const std::string& description) {
  CLI::Option* option = command.add_option("--labels", labels, description);
  slicerParameter(command.add_option("--grid", grid,
                                     "Scan whose grid an RT Structure Set given as --labels is read onto (NIfTI, "
                                     "NRRD, MetaImage, DICOM folder); only for an RT Structure Set"),
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
  LabelMap map = io::readDicomRtStruct(labels, io::describeScan(grid).geometry);
  if (!table.empty()) {
    // As for a DICOM SEG, an explicit table wins; ROIs it does not list keep their own names unless the
    // table gives that name to another id (a name must pick one label).
    LabelTable named = io::readLabelTable(table);
    for (LabelEntry roi : map.table.entries) {
      if (named.find(roi.id)) continue;
      if (named.find(roi.name)) roi.name = "label_" + std::to_string(roi.id);
      named.add(std::move(roi));
    }
    map.table = std::move(named);
  }
  return map;
}

}  // namespace vesalius::cli
