// Runs the picker: reads the inputs, opens the window, plays recorded events or runs the event loop,
// autosaves on exit. Returns the process exit code; throws vesalius::Error on bad input or usage.
#pragma once

#include "picker_options.h"

namespace vesalius::picker {

int runPicker(const PickerOptions& options);

}  // namespace vesalius::picker
