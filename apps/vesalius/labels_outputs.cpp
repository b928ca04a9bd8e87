#include "labels_outputs.h"

#include "vesalius/io/dicom_rtstruct.h"
#include "vesalius/io/dicom_seg.h"
#include "vesalius/io/image_io.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <utility>

namespace vesalius::cli {

namespace {

std::string sizeText(const GridGeometry& g) {
  return std::to_string(g.size.x()) + "x" + std::to_string(g.size.y()) + "x" + std::to_string(g.size.z());
}

std::vector<std::int64_t> voxelsPerId(const Grid<Label>& labels) {
  std::vector<std::int64_t> voxels(65536, 0);
  for (Label v : labels.values) ++voxels[v];
  return voxels;
}

}  // namespace

LabelsInput::LabelsInput(std::string labelsPath, std::string gridPath, LabelMap labelMap)
    : path(std::move(labelsPath)),
      grid(std::move(gridPath)),
      map(std::move(labelMap)),
      voxels(voxelsPerId(map.labels)) {}

std::string LabelsInput::name(Label id) const {
  const LabelEntry* e = map.table.find(id);
  return e ? e->name + " (" + std::to_string(id) + ")" : std::to_string(id);
}

Label LabelsInput::label(const std::string& idOrName) const {
  const Label id = resolveLabel(map, idOrName, path);
  if (voxels[id] == 0) throw BadInput(path, "no voxel has label " + name(id));
  return id;
}

std::vector<Label> LabelsInput::labels(const std::vector<std::string>& idsOrNames) const {
  std::vector<Label> ids;
  for (const std::string& s : idsOrNames) {
    const Label id = label(s);
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) throw UsageError("label " + name(id) + " is given twice");
    ids.push_back(id);
  }
  return ids;
}

std::vector<Label> LabelsInput::presentExcept(const std::vector<Label>& ids) const {
  std::vector<Label> out;
  for (std::size_t id = 1; id < voxels.size(); ++id)
    if (voxels[id] > 0 && std::find(ids.begin(), ids.end(), Label(id)) == ids.end()) out.push_back(Label(id));
  return out;
}

void refuseInputsAsOutputs(const std::string& labels, const std::string& table, const std::string& out) {
  const std::string inputTable = table.empty() ? io::labelTableSidecarPath(labels) : table;
  for (const std::string& written : {out, io::labelTableSidecarPath(out)})
    for (const std::string& in : {labels, inputTable}) {
      std::error_code ec;
      if (std::filesystem::equivalent(in, written, ec))
        throw UsageError(written + ": is an input of this command; choose another --out");
    }
}

void checkDicomSeriesOption(const std::string& dicomSeries, const std::string& out) {
  if (!dicomSeries.empty() && !io::isDicomSegPath(out) && !io::isDicomRtStructPath(out))
    throw UsageError("--dicom-series names the series a DICOM segmentation or RT Structure Set refers to; give an "
                     "--out ending .dcm");
}

void writeLabelsOutputs(const LabelsInput& input, const LabelMap& edited, const std::vector<SummaryRow>& rows,
                        const std::string& out, const std::string& dicomSeries, const CommonOptions& common,
                        io::Report& report) {
  const bool rtStruct = io::isDicomRtStructPath(out);
  if (io::isDicomSegPath(out) || rtStruct) {
    // A structure set refers to no grid: the scan it was read onto is the series it belongs to.
    const std::string series = !dicomSeries.empty() ? dicomSeries : !input.grid.empty() ? input.grid : input.path;
    const std::optional<io::DicomSourceSeries> source = io::readDicomSource(series);
    if (rtStruct) io::writeDicomRtStruct(out, edited, source ? &*source : nullptr, common.writeOptions());
    else io::writeDicomSeg(out, edited, source ? &*source : nullptr, common.writeOptions());
    if (source) report.input("dicom_series", series);
  } else {
    io::writeLabelMap(out, edited, common.writeOptions());
  }
  const std::string table = io::labelTableSidecarPath(out);
  report.output("labels", out);
  report.output("table", table);

  const std::vector<std::int64_t> after = voxelsPerId(edited.labels);
  const double voxelMl = input.map.labels.geometry.spacing.prod() / 1000.0;
  auto sum = [](const std::vector<std::int64_t>& voxels, const std::vector<Label>& ids) {
    std::int64_t n = 0;
    for (Label id : ids) n += voxels[id];
    return n;
  };
  for (const SummaryRow& row : rows) {
    const std::int64_t b = sum(input.voxels, row.before), a = sum(after, row.after);
    char line[160];
    std::snprintf(line, sizeof line, ": %lld -> %lld voxels, %.1f -> %.1f mL", (long long)b, (long long)a,
                  double(b) * voxelMl, double(a) * voxelMl);
    std::cout << row.name << line << '\n';
    report.metric(row.name, {{"voxels_before", b},
                             {"voxels_after", a},
                             {"ml_before", double(b) * voxelMl},
                             {"ml_after", double(a) * voxelMl}});
  }
  const std::string before = sizeText(input.map.labels.geometry), now = sizeText(edited.labels.geometry);
  if (before != now) std::cout << "grid: " << before << " -> " << now << " voxels\n";

  std::cout << "labels: " << out << "\ntable: " << table << '\n';
}

}  // namespace vesalius::cli
