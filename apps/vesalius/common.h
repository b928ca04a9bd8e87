// What every `vesalius` subcommand shares: the common options and how a command's run is wrapped.
#pragma once

#include "vesalius/core/atomic_file.h"
#include "vesalius/core/error.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/io/report.h"

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
  // Writes the report if one was asked for.
  void finish(const io::Report& report) const;
};

// Adds --progress, --force and --report to a subcommand; an existing --report without --force is refused
// when the options are parsed.
void addCommonOptions(CLI::App& command, CommonOptions& options);

// The one line `vesalius` prints for `error`: a BadInput raised by library code that knows no file (a
// scan that is constant, points that are collinear) is prefixed with the command's input files.
std::string errorMessage(const Error& error);

// A label chosen with --label: an id, or a name from the label table of the map read from `labelsPath`
// (LabelTable::resolve: names case-insensitive). Throws UsageError naming `labelsPath` if it matches
// nothing.
Label resolveLabel(const LabelMap& map, const std::string& idOrName, const std::string& labelsPath);

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
