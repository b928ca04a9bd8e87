// What every `vesalius` command does around its own work: one JSON report (--report) and one progress
// bar (--progress) for the whole run, and the report written when the work is done. A command's run
// function is then its options, its library call and its outputs:
//
//   void runSegment(const SegmentOptions& o, CommandRun& run) {
//     run.report.input("scan", o.scan);
//     const LabelMap labels = segmentation::segmentCtTissues(io::readScan(o.scan), {}, &run.progress);
//     io::writeLabelMap(o.out, labels, o.common.writeOptions());
//     run.report.output("labels", o.out);
//   }
//   cmd->callback([o] { runCommand("segment", o->common, [&](CommandRun& run) { runSegment(*o, run); }); });
#pragma once

#include "common.h"

#include "vesalius/core/progress.h"
#include "vesalius/io/report.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::cli {

// What a command's work fills in and reports to.
struct CommandRun {
  io::Report report;  // inputs, parameters, stage times, outputs, metrics
  Progress progress;  // one bar over the whole command; pass &progress to the library
};

// A command's own stages by the names it (or the pipeline it calls) begins them with, and their relative
// costs, as a run's stage times measure them (Progress::plan).
using StagePlan = std::vector<std::pair<std::string, double>>;

// Runs `work` with a report named `command` (its "command" key) and a progress in --progress's style
// planned by `plan`, then writes the report when --report names a file. Work that throws writes no
// report; the error goes on to main, which prints it and exits with its code.
void runCommand(const std::string& command, const CommonOptions& common, const std::function<void(CommandRun&)>& work,
                const StagePlan& plan = {});

}  // namespace vesalius::cli
