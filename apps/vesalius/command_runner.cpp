#include "command_runner.h"

namespace vesalius::cli {

void runCommand(const std::string& command, const CommonOptions& common, const std::function<void(CommandRun&)>& work,
                const StagePlan& plan) {
  CommandRun run{io::Report(command), Progress(common.progressStyle())};
  if (!plan.empty()) run.progress.plan(plan);
  work(run);
  if (!common.report.empty()) run.report.write(common.report, common.writeOptions());
}

}  // namespace vesalius::cli
