// vesalius markers sample as a function, so that other commands can run it (the demo samples the liver).
#pragma once

#include "common.h"

#include <cstdint>
#include <string>

namespace vesalius::cli {

struct SampleOptions {
  std::string labels, table, label, out;
  int count = 100;
  std::uint64_t seed = 1;
  CommonOptions common;
};

// ICP markers spread over the boundary of `label` in `labels`, written to `out`; prints one summary line.
void runSample(const SampleOptions& o);

}  // namespace vesalius::cli
