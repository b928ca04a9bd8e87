// What every `vesalius` subcommand shares: the common options and their checks, the 3D Slicer module
// description, error messages and labels chosen by id or name.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/core/skeleton.h"

#include <CLI/CLI.hpp>

#include <memory>
#include <string>

namespace vesalius::cli {

struct CommonOptions {
  std::string progress = "auto";  // none | bar | slicer | auto
  bool force = false;             // replace existing outputs
  std::string report;             // JSON report path, empty for none

  WriteOptions writeOptions() const { return WriteOptions{force}; }
  Progress::Style progressStyle() const { return Progress::parseStyle(progress); }
};

// Adds --progress, --force, --report and --xml to a subcommand; an existing --report without --force is
// refused when the options are parsed. --xml prints slicerXml(command) and exits 0 before any other option
// is checked, so that 3D Slicer can run `vesalius COMMAND --xml` without the command's required options.
void addCommonOptions(CLI::App& command, CommonOptions& options);

// What a 3D Slicer CLI module parameter is, where CLI11 cannot tell: an image (a volume node in Slicer), a
// label map image, a geometry (a model node), a file or a directory.
enum class SlicerKind { Image, LabelImage, Geometry, File, Directory };

// Marks `option` as a Slicer parameter of `kind`, read (`output` false) or written by the command;
// `fileExtensions` (".nii.gz,.nrrd") tells Slicer the file types. Returns `option`.
CLI::Option* slicerParameter(CLI::Option* option, SlicerKind kind, bool output, const std::string& fileExtensions = "");

// The command's 3D Slicer CLI module description (SlicerExecutionModel XML, ModuleDescriptionParser's
// rules): one parameter per option (--help and --xml aside), each named and long-flagged after the option
// with '-' as '_' (Slicer allows only letters, digits and '_'; see slicerArguments). Types come from CLI11
// (a flag is a <boolean>, an int an <integer>, a double a <double>, an IsMember check a
// <string-enumeration>, a positional argument an <index>ed parameter), kinds from slicerParameter, else by
// the conventions of the commands: --scan is an input image, --labels and --organs input label maps, an
// output option (named as checkInputsAndOutputs names them) a file, or a directory when its description
// speaks of a folder or directory; any other text a <string>. --progress defaults to slicer in it.
std::string slicerXml(const CLI::App& command);

// Slicer passes the long flags of slicerXml (`--skin_thickness 2`); turns each `--a_b` or `--a_b=v` in
// argv into the option's own `--a-b` in place. Values are left alone.
void slicerArguments(int argc, char** argv);

// The one line `vesalius` prints for `error`: a BadInput raised by library code that knows no file (a
// scan that is constant, points that are collinear) is prefixed with the command's input files.
std::string errorMessage(const Error& error);

// A label chosen with --label: an id, or a name from the label table of the map read from `labelsPath`
// (LabelTable::resolve: names case-insensitive). Throws UsageError naming `labelsPath` if it matches
// nothing.
Label resolveLabel(const LabelMap& map, const std::string& idOrName, const std::string& labelsPath);

// A warning line on stderr when a rig's tets are more than twice the target asked (`option` names it): its
// surfaces stopped above their budgets (rigging/label_regions.h).
void warnIfOverTetTarget(long tets, long targetTets, const std::string& option);

// Each subcommand registers itself on the top-level app.
void addInfoCommand(CLI::App& app);
void addMarkersCommand(CLI::App& app);
void addSegmentCommand(CLI::App& app);
void addLabelsCommand(CLI::App& app);
void addSurfaceCommand(CLI::App& app);
void addTetmeshCommand(CLI::App& app);
void addFitCommand(CLI::App& app);
void addSeparateCommand(CLI::App& app);
void addDemoCommand(CLI::App& app);
void addRigCommand(CLI::App& app);
void addPoseCommand(CLI::App& app);
void addFatCommand(CLI::App& app);
void addReferenceCommand(CLI::App& app);
void addTransferCommand(CLI::App& app);
void addPatientCommand(CLI::App& app);

}  // namespace vesalius::cli
