// Names that come from files (a label, a tissue, a mesh) used as file names.
#pragma once

#include <string>

namespace vesalius {

// `name` made into a file name that stays in the folder it is put in: every character but ASCII letters,
// digits, '-' and '_' becomes '_' ("../x" -> "___x"); an empty name becomes "unnamed".
std::string safeFileName(const std::string& name);

}  // namespace vesalius
