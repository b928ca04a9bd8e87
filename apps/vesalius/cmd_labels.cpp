// vesalius labels: edits of a label map (extract, merge, relabel, connected components, hole filling,
// morphology in mm, cropping), each written as a new map with its label table beside it.
//
// The operations are the library's (segmentation/label_edit.h, label_ops.h). What the command adds is
// how a per-label mask edit goes back into the map: voxels a label loses become background, voxels it
// gains are taken from the background only, unless --overwrite lets it take them from other labels too.
// Keeping N > 1 largest components is not offered: label_ops.h gives the largest one, or all components
// above a size.
#include "common.h"

#include "vesalius/core/error.h"
#include "vesalius/io/image_io.h"
#include "vesalius/segmentation/label_edit.h"
#include "vesalius/segmentation/label_ops.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

namespace vesalius::cli {

namespace {

namespace seg = segmentation;

struct LabelsOptions {
  std::string labels, table, out;
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

std::vector<std::int64_t> voxelsPerId(const Grid<Label>& labels) {
  std::vector<std::int64_t> voxels(65536, 0);
  for (Label v : labels.values) ++voxels[v];
  return voxels;
}

// The map being edited, its voxel count per id, and the labels the user named.
struct Input {
  const LabelsOptions& o;
  LabelMap map;
  std::vector<std::int64_t> voxels;  // by id

  Input(const LabelsOptions& options, LabelMap labelMap)
      : o(options), map(std::move(labelMap)), voxels(voxelsPerId(map.labels)) {}

  // "liver (5)", or "5" for an id without a table entry.
  std::string name(Label id) const {
    const LabelEntry* e = map.table.find(id);
    return e ? e->name + " (" + std::to_string(id) + ")" : std::to_string(id);
  }
  // An id or name that must have voxels: editing a label the map does not hold is a mistake.
  Label label(const std::string& idOrName) const {
    const Label id = resolveLabel(map, idOrName, o.labels);
    if (voxels[id] == 0) throw BadInput(o.labels, "no voxel has label " + name(id));
    return id;
  }
  std::vector<Label> labels(const std::vector<std::string>& idsOrNames) const {
    std::vector<Label> ids;
    for (const std::string& s : idsOrNames) {
      const Label id = label(s);
      if (std::find(ids.begin(), ids.end(), id) != ids.end()) throw UsageError("label " + name(id) + " is given twice");
      ids.push_back(id);
    }
    return ids;
  }
  // The ids with voxels, but not those of `ids`.
  std::vector<Label> presentExcept(const std::vector<Label>& ids) const {
    std::vector<Label> out;
    for (std::size_t id = 1; id < voxels.size(); ++id)
      if (voxels[id] > 0 && std::find(ids.begin(), ids.end(), Label(id)) == ids.end()) out.push_back(Label(id));
    return out;
  }
};

// A summary line: the voxels of ids `before` in the input against those of ids `after` in the output.
struct SummaryRow {
  std::string name;
  std::vector<Label> before, after;
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

// Replaces each selected label, in the order given, by `edit` of its mask (see the header comment).
Edit editMasks(const Input& in, const std::function<seg::Mask(const seg::Mask&)>& edit) {
  Edit e{in.map, {}};
  const std::vector<Label> ids = in.labels(in.o.selected);
  for (Label id : ids) {
    const seg::Mask before = seg::maskOf(e.map.labels, id);
    const seg::Mask after = edit(before);
    seg::Mask gained = seg::maskAndNot(after, before);
    if (!in.o.overwrite) gained = seg::maskAnd(gained, seg::maskOf(e.map.labels, 0));
    seg::paintMask(e.map.labels, seg::maskAndNot(before, after), 0);
    seg::paintMask(e.map.labels, gained, id);
    e.rows.push_back({in.name(id), {id}, {id}});
  }
  if (in.o.overwrite) e.rows.push_back(othersRow(in, ids));
  return e;
}

Edit components(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("largest", in.o.largest);
  report.parameter("min_ml", in.o.minMl);
  if (!(in.o.minMl >= 0) || !std::isfinite(in.o.minMl)) throw UsageError("--min-ml must be a volume in mL >= 0");
  if (in.o.largest == (in.o.minMl > 0)) throw UsageError("labels components: give one of --largest and --min-ml");
  const double voxelMl = in.map.labels.geometry.spacing.prod() / 1000.0;
  const auto minVoxels = std::int64_t(std::ceil(in.o.minMl / voxelMl - 1e-9));
  return editMasks(in, [&](const seg::Mask& mask) {
    return in.o.largest ? seg::largestComponent(mask) : seg::removeSmallComponents(mask, minVoxels);
  });
}

Edit fill(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("axial", in.o.axial);
  report.parameter("overwrite", in.o.overwrite);
  const int axis = seg::axialAxis(in.map.labels.geometry);
  return editMasks(in, [&](const seg::Mask& mask) {
    return in.o.axial ? seg::fillHolesSliceWise(mask, axis) : seg::fillHoles3d(mask);
  });
}

Edit morph(const Input& in, io::Report& report) {
  report.parameter("label", in.o.selected);
  report.parameter("op", in.o.op);
  report.parameter("radius_mm", in.o.radiusMm);
  report.parameter("overwrite", in.o.overwrite);
  const double r = in.o.radiusMm;
  if (!(r > 0) || !std::isfinite(r)) throw UsageError("--radius-mm must be a number of mm > 0");
  const std::map<std::string, seg::Mask (*)(const seg::Mask&, double)> ops{
      {"dilate", seg::dilateMm}, {"erode", seg::erodeMm}, {"open", seg::openMm}, {"close", seg::closeMm}};
  const auto op = ops.at(in.o.op);
  return editMasks(in, [&](const seg::Mask& mask) { return op(mask, r); });
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

std::string sizeText(const GridGeometry& g) {
  return std::to_string(g.size.x()) + "x" + std::to_string(g.size.y()) + "x" + std::to_string(g.size.z());
}

// Voxels and millilitres per summary row, before and after, printed and put in the report.
void summarize(const Input& in, const Edit& e, io::Report& report) {
  const std::vector<std::int64_t> after = voxelsPerId(e.map.labels);
  const double voxelMl = in.map.labels.geometry.spacing.prod() / 1000.0;
  auto sum = [](const std::vector<std::int64_t>& voxels, const std::vector<Label>& ids) {
    std::int64_t n = 0;
    for (Label id : ids) n += voxels[id];
    return n;
  };
  for (const SummaryRow& row : e.rows) {
    const std::int64_t b = sum(in.voxels, row.before), a = sum(after, row.after);
    char line[160];
    std::snprintf(line, sizeof line, ": %lld -> %lld voxels, %.1f -> %.1f mL", (long long)b, (long long)a,
                  double(b) * voxelMl, double(a) * voxelMl);
    std::cout << row.name << line << '\n';
    report.metric(row.name, {{"voxels_before", b},
                             {"voxels_after", a},
                             {"ml_before", double(b) * voxelMl},
                             {"ml_after", double(a) * voxelMl}});
  }
  const std::string before = sizeText(in.map.labels.geometry), now = sizeText(e.map.labels.geometry);
  if (before != now) std::cout << "grid: " << before << " -> " << now << " voxels\n";
}

// The output map and its table may not replace the input map or the table it was read with.
void refuseInputsAsOutputs(const LabelsOptions& o) {
  const std::string inputTable = o.table.empty() ? io::labelTableSidecarPath(o.labels) : o.table;
  for (const std::string& out : {o.out, io::labelTableSidecarPath(o.out)})
    for (const std::string& in : {o.labels, inputTable}) {
      std::error_code ec;
      if (std::filesystem::equivalent(in, out, ec))
        throw UsageError(out + ": is an input of this command; choose another --out");
    }
}

void runLabels(const LabelsOptions& o, const std::string& action, const Action& act) {
  io::Report report("labels " + action);
  report.input("labels", o.labels);
  if (!o.table.empty()) report.input("table", o.table);
  refuseInputsAsOutputs(o);
  const Input in(o, io::readLabelMap(o.labels, o.table));
  Edit e;
  {
    auto timer = report.time(action);
    e = act(in, report);
  }
  io::writeLabelMap(o.out, e.map, o.common.writeOptions());
  const std::string table = io::labelTableSidecarPath(o.out);
  report.output("labels", o.out);
  report.output("table", table);
  summarize(in, e, report);
  std::cout << "labels: " << o.out << "\ntable: " << table << '\n';
  o.common.finish(report);
}

// One action: --labels, --table, then its own options (`addOwn`), then --out and the common options.
void addAction(CLI::App& labels, const std::string& name, const std::string& description, const std::string& example,
               const Action& act, const std::function<void(CLI::App&, LabelsOptions&)>& addOwn) {
  auto o = std::make_shared<LabelsOptions>();
  CLI::App* cmd = labels.add_subcommand(name, description);
  cmd->add_option("--labels", o->labels, "Label map (NIfTI, NRRD, MetaImage)")->required();
  cmd->add_option("--table", o->table, "Label table (.tsv or Slicer .ctbl); default: the one beside the label map");
  addOwn(*cmd, *o);
  cmd->add_option("--out", o->out, "Label map to write (.nii.gz, .nrrd, .mha); a .tsv label table goes beside it")
      ->required();
  addCommonOptions(*cmd, o->common);
  cmd->footer("Example:\n  " + example);
  cmd->callback([o, name, act] { runLabels(*o, name, act); });
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
