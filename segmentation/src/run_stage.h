// One named Progress stage around a piece of work, for the tissue classifiers (internal).
#pragma once

#include "vesalius/core/progress.h"

#include <string>

namespace vesalius::segmentation::detail {

// Runs `work` as stage `name` of `progress` (which may be null), reporting it complete at the end.
template <class Work>
void runStage(Progress* progress, const std::string& name, Work&& work) {
  if (progress) progress->begin(name);
  work();
  if (progress) {
    progress->update(1.0);
    progress->end();
  }
}

}  // namespace vesalius::segmentation::detail
