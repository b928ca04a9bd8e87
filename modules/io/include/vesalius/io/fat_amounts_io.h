// The fat editor's per-bone amounts file, as `fat edit --amounts` and `transfer --fat-amounts` take it:
// a JSON object of bone (or group) names and amounts in [0, 1], {"pelvis": 0.4, "femur_l": 0.2}
// (docs/formats.md). fat::boneFatFromAmounts checks the names and the values.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace vesalius::io {

// The file's pairs in its order; a value that is not a number is NaN, which fat::boneFatFromAmounts
// refuses by name. Throws BadInput naming `path` for a file that is not a JSON object.
std::vector<std::pair<std::string, double>> readFatAmounts(const std::string& path);

}  // namespace vesalius::io
