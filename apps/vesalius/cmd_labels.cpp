// vesalius labels: edits of a label map (extract, merge, relabel, connected components, hole filling,
// morphology in mm, cropping), each written as a new map with its label table beside it.
//
// The operations are the library's (segmentation/label_edit.h, label_mask_edit.h: a per-label mask edit
// goes back into the map taking voxels from the background only, unless --overwrite); the command
// resolves the labels the user names and sums up what changed (labels_outputs.h). Keeping N > 1 largest
// components is not offered: label_ops.h gives the largest one, or all components above a size.
#include "command_runner.h"
#include "common.h"
#include "label_map_input.h"
#include "labels_outputs.h"

#include "vesalius/core/error.h"
#include "vesalius/segmentation/label_edit.h"
#include "vesalius/segmentation/label_mask_edit.h"
#include "vesalius/segmentation/label_ops.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <sstream>

namespace vesalius::cli {

namespace {

namespace seg = segmentation;
using E = seg::MaskEdit;

struct LabelsOptions {
  std::string labels, table, out, dicomSeries, grid;
  std::vector<std::string> selected;  // --label, or --to-label for crop
  std::string into;                   // merge: ID[:NAME]
  std::vector<std::string> maps;      // relabel: OLD=NEW
  bool largest = false;               // components
  double minMl = 0;                   // components
  bool axial = false;                 // fill
  std::string op;                     // morph
  double radiusMm = 0;                // morph
  double marginMm = 0;                // crop
  bool overwrite = false;             // fill, morph
  CommonOptions common;
};

// The map being edited with the action's options.
struct Input : LabelsInput {
  const LabelsOptions& o;
  Input(const LabelsOptions& op, io::Report& report)
      : LabelsInput(op.labels, op.grid, readLabelsOption(op.labels, op.table, op.grid, report)), o(op) {}
};

struct Edit {
  LabelMap map;
  std::vector<SummaryRow> rows;
};

using Action = std::function<Edit(const Input&, io::Report&)>;

// "5" -> 5; nullopt unless the text is a whole number 0..65535.
std::optional<Label> parseId(const std::string& text) {
  if (text.empty() || text.size() > 5 || text.find_first_not_of("0123456789") != std::string::npos) return {};
  const long id = std::stol(text);
  if (id > 65535) return {};
  return Label(id);
}

SummaryRow othersRow(const Input& in, const std::vector<Label>& ids) {
  const std::vector<Label> others = in.presentExcept(ids);
  return {ids.empty() ? "all labels" : "other labels", others, others};
}

Edit extract(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  const std::vector<Label> ids = in.labels(in.o.selected);
  Edit e{seg::extractLabels(in.map, ids), {}};
  for (Label id : ids) e.rows.push_back({in.name(id), {id}, {id}});
  e.rows.push_back(othersRow(in, ids));
  return e;
}

// --into ID[:NAME]; without a name the entry keeps the table's name (and colour) for ID. A name may not
// be left on two ids, where names would no longer pick one label.
LabelEntry mergeTarget(const Input& in, const std::vector<Label>& merged) {
  const std::string& s = in.o.into;
  const std::string idText = s.substr(0, s.find(':'));
  const std::optional<Label> id = parseId(idText);
  if (!id || *id == 0) throw UsageError("--into '" + s + "': expected ID or ID:NAME with ID 1..65535");
  LabelEntry entry{*id, s.size() > idText.size() ? s.substr(idText.size() + 1) : "", defaultLabelColor(*id)};
  if (const LabelEntry* existing = in.map.table.find(*id)) {
    entry.color = existing->color;
    if (entry.name.empty()) entry.name = existing->name;
  }
  if (entry.name.empty())
    throw UsageError("--into '" + s + "': id " + idText + " is new; name it with --into " + idText + ":NAME");
  const LabelEntry* named = in.map.table.find(entry.name);
  if (named && named->id != entry.id && std::find(merged.begin(), merged.end(), named->id) == merged.end())
    throw UsageError("--into '" + s + "': the name " + entry.name + " belongs to label " + in.name(named->id));
  return entry;
}

Edit merge(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("into", in.o.into);
  const std::vector<Label> ids = in.labels(in.o.selected);
  const LabelEntry into = mergeTarget(in, ids);
  SummaryRow row{into.name + " (" + std::to_string(into.id) + ") <-", ids, {into.id}};
  for (Label id : ids) row.name += (id == ids.front() ? " " : " + ") + in.name(id);
  // Merging into a label that already has voxels joins them, so they count as before too.
  if (std::find(ids.begin(), ids.end(), into.id) == ids.end() && in.voxels[into.id] > 0) {
    row.before.push_back(into.id);
    row.name += " + " + in.name(into.id);
  }
  return {seg::mergeLabels(in.map, ids, into), {row}};
}

Edit relabelIds(const Input& in, io::Report& report) {
  report.parameter("map", in.o.maps);
  std::map<Label, Label> idMap;
  Edit e;
  for (const std::string& m : in.o.maps) {
    const std::size_t eq = m.rfind('=');
    const std::optional<Label> to = eq == std::string::npos || eq == 0 ? std::nullopt : parseId(m.substr(eq + 1));
    if (!to)
      throw UsageError("--map '" + m + "': expected OLD=NEW, OLD a label id or name, NEW an id 0..65535 (0 deletes)");
    const Label from = in.label(m.substr(0, eq));
    if (!idMap.emplace(from, *to).second) throw UsageError("--map: label " + in.name(from) + " is mapped twice");
    e.rows.push_back({in.name(from) + " -> " + (*to ? std::to_string(*to) : "deleted"),
                      {from},
                      *to ? std::vector<Label>{*to} : std::vector<Label>{}});
  }
  e.map = seg::relabel(in.map, idMap);
  return e;
}

// Each selected label, in the order given, replaced by the edit of its mask (label_mask_edit.h).
Edit editMasks(const Input& in, seg::LabelMaskEditOptions options) {
  const std::vector<Label> ids = in.labels(in.o.selected);
  options.overwrite = in.o.overwrite;
  Edit e{seg::editLabelMasks(in.map, ids, options), {}};
  for (Label id : ids) e.rows.push_back({in.name(id), {id}, {id}});
  if (in.o.overwrite) e.rows.push_back(othersRow(in, ids));
  return e;
}

Edit components(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("largest", in.o.largest);
  report.parameter("min_ml", in.o.minMl);
  if (!(in.o.minMl >= 0) || !std::isfinite(in.o.minMl)) throw UsageError("--min-ml must be a volume in mL >= 0");
  if (in.o.largest == (in.o.minMl > 0)) throw UsageError("labels components: give one of --largest and --min-ml");
  return editMasks(in, {in.o.largest ? E::LargestComponent : E::DropSmallComponents, in.o.minMl});
}

Edit fill(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("axial", in.o.axial);
  report.parameter("overwrite", in.o.overwrite);
  return editMasks(in, {in.o.axial ? E::FillHolesAxial : E::FillHoles});
}

Edit morph(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("op", in.o.op);
  report.parameter("radius_mm", in.o.radiusMm);
  report.parameter("overwrite", in.o.overwrite);
  const double r = in.o.radiusMm;
  if (!(r > 0) || !std::isfinite(r)) throw UsageError("--radius-mm must be a number of mm > 0");
  const std::map<std::string, E> ops{
      {"dilate", E::Dilate}, {"erode", E::Erode}, {"open", E::Open}, {"close", E::Close}};
  return editMasks(in, {ops.at(in.o.op), 0, r});
}

Edit crop(const Input& in, io::Report& report) {
  report.parameter("to_label", in.o.selected);
  report.parameter("margin_mm", in.o.marginMm);
  // A margin beyond the map's own extent keeps the whole map whatever the labels, and huge ones overflow
  // the voxel arithmetic, so they are refused (negative and NaN margins by maskBounds).
  const GridGeometry& grid = in.map.labels.geometry;
  const double extent = (grid.size.cast<double>().array() * grid.spacing.array()).maxCoeff();
  if (in.o.marginMm > extent) {
    std::ostringstream text;
    text << "labels crop: --margin-mm must be from 0 to " << extent << " mm (the largest extent of "
         << in.o.labels << "), not " << in.o.marginMm;
    throw UsageError(text.str());
  }
  const std::vector<Label> ids = in.labels(in.o.selected);
  if (ids.empty() && in.presentExcept({}).empty())
    throw BadInput(in.o.labels, "every voxel is background; nothing to crop to");
  seg::Mask mask = ids.empty() ? seg::nonZeroMask(in.map.labels) : seg::maskOf(in.map.labels, ids.front());
  for (std::size_t n = 1; n < ids.size(); ++n) mask = seg::maskOr(mask, seg::maskOf(in.map.labels, ids[n]));
  const seg::VoxelBox box = seg::maskBounds(mask, in.o.marginMm);
  Edit e{seg::cropLabelMap(in.map, box), {}};
  for (Label id : ids) e.rows.push_back({in.name(id), {id}, {id}});
  e.rows.push_back(othersRow(in, ids));
  return e;
}

void runLabels(const LabelsOptions& o, const std::string& action, const Action& act, CommandRun& run) {
  run.report.input("labels", o.labels);
  if (!o.table.empty()) run.report.input("table", o.table);
  refuseInputsAsOutputs(o.labels, o.table, o.out);
  checkDicomSeriesOption(o.dicomSeries, o.out);
  const Input in(o, run.report);
  Edit e;
  {
    auto timer = run.report.time(action);
    e = act(in, run.report);
  }
  writeLabelsOutputs(in, e.map, e.rows, o.out, o.dicomSeries, o.common, run.report);
}

// One action: --labels, --table, then its own options (`addOwn`), then --out and the common options.
void addAction(CLI::App& labels, const std::string& name, const std::string& description, const std::string& example,
               const Action& act, const std::function<void(CLI::App&, LabelsOptions&)>& addOwn) {
  auto o = std::make_shared<LabelsOptions>();
  CLI::App* cmd = labels.add_subcommand(name, description);
  addLabelsOption(*cmd, o->labels, o->grid, kLabelsHelp)->required();
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  addOwn(*cmd, *o);
  cmd->add_option("--out", o->out, kOutHelp)->required();
  cmd->add_option("--dicom-series", o->dicomSeries, kDicomSeriesHelp);
  addCommonOptions(*cmd, o->common);
  cmd->footer("Example:\n  " + example);
  cmd->callback([o, name, act] {
    runCommand("labels " + name, o->common, [&](CommandRun& run) { runLabels(*o, name, act, run); });
  });
}

constexpr const char* kLabelHelp = "Label id or name, repeatable";
constexpr const char* kOverwriteHelp = "Let the label take voxels of other labels (default: only background voxels)";

void addFillAndMorph(CLI::App& labels) {
  addAction(labels, "fill", "Fill the holes of labels (background enclosed by the label)",
            "vesalius labels fill --labels labels.nii.gz --label liver --out liver-filled.nii.gz", fill,
            [](CLI::App& cmd, LabelsOptions& o) {
              cmd.add_option("--label", o.selected, kLabelHelp)->required();
              cmd.add_flag("--axial", o.axial,
                           "Fill holes per axial slice: also closes cavities cut open by the first or last slice");
              cmd.add_flag("--overwrite", o.overwrite, kOverwriteHelp);
            });
  addAction(labels, "morph", "Dilate, erode, open or close labels with a ball of a radius in mm",
            "vesalius labels morph --labels labels.nii.gz --label liver --op close --radius-mm 3 "
            "--out liver-closed.nii.gz",
            morph, [](CLI::App& cmd, LabelsOptions& o) {
              cmd.add_option("--label", o.selected, kLabelHelp)->required();
              cmd.add_option("--op", o.op, "dilate, erode, open (erode then dilate) or close (dilate then erode)")
                  ->required()
                  ->check(CLI::IsMember({"dilate", "erode", "open", "close"}));
              cmd.add_option("--radius-mm", o.radiusMm, "Ball radius in mm (voxel centres within it)")->required();
              cmd.add_flag("--overwrite", o.overwrite, kOverwriteHelp);
            });
}

}  // namespace

void addLabelsCommand(CLI::App& app) {
  CLI::App* labels = app.add_subcommand("labels",
                                        "Edit a label map: extract, merge, relabel, components, fill, "
                                        "morph, crop");
  labels->require_subcommand(1);
  labels->footer(
      "Run 'vesalius labels ACTION --help' for the options of each action.\nExample:\n  vesalius labels "
      "extract --labels labels.nii.gz --label liver --label spleen --out organs.nii.gz");
  addAction(*labels, "extract", "Keep the given labels; every other voxel becomes background",
            "vesalius labels extract --labels labels.nii.gz --label liver --label spleen --out organs.nii.gz", extract,
            [](CLI::App& cmd, LabelsOptions& o) { cmd.add_option("--label", o.selected, kLabelHelp)->required(); });
  addAction(*labels, "merge", "Merge labels into one id",
            "vesalius labels merge --labels labels.nii.gz --label hip_left --label hip_right --into 200:hips "
            "--out hips.nii.gz",
            merge, [](CLI::App& cmd, LabelsOptions& o) {
              cmd.add_option("--label", o.selected, kLabelHelp)->required();
              cmd.add_option("--into", o.into, "ID or ID:NAME of the merged label (a new id needs a name)")->required();
            });
  addAction(
      *labels, "relabel", "Change label ids; NEW 0 deletes a label",
      "vesalius labels relabel --labels labels.nii.gz --map liver=1 --map spleen=0 --out relabelled.nii.gz", relabelIds,
      [](CLI::App& cmd, LabelsOptions& o) {
        cmd.add_option("--map", o.maps, "OLD=NEW, OLD an id or name, NEW an id (0 deletes); repeatable")->required();
      });
  addAction(*labels, "components", "Keep the largest connected component of labels, or those above a volume",
            "vesalius labels components --labels labels.nii.gz --label liver --largest --out liver-one.nii.gz",
            components, [](CLI::App& cmd, LabelsOptions& o) {
              cmd.add_option("--label", o.selected, kLabelHelp)->required();
              cmd.add_flag("--largest", o.largest, "Keep the largest 26-connected component");
              cmd.add_option("--min-ml", o.minMl, "Keep the 26-connected components of at least this volume (mL)");
            });
  addFillAndMorph(*labels);
  addAction(*labels, "crop", "Crop the map to the bounds of labels (default: of every labelled voxel)",
            "vesalius labels crop --labels labels.nii.gz --to-label liver --margin-mm 10 --out liver-box.nii.gz", crop,
            [](CLI::App& cmd, LabelsOptions& o) {
              cmd.add_option("--to-label", o.selected, "Label id or name to crop to, repeatable");
              cmd.add_option("--margin-mm", o.marginMm, "Margin around the bounds in mm")->capture_default_str();
            });
}

}  // namespace vesalius::cli
