// Runs the poser: reads the anatomy directory and the motion, opens the window on options.frame, plays
// recorded events or runs the event loop. Returns the process exit code; throws vesalius::Error on bad
// input (BadInput), impossible options or no display (UsageError).
#pragma once

#include "poser_options.h"

namespace vesalius::poser {

int runPoser(const PoserOptions& options);

}  // namespace vesalius::poser
