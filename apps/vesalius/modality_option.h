// `--modality auto|ct|mri` of the commands that classify a scan's tissues (`segment`, `patient`).
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/segmentation/scan_modality.h"

#include <CLI/CLI.hpp>

#include <string>

namespace vesalius::cli {

// The option, into `word` (default auto).
void addModalityOption(CLI::App& command, std::string& word);

// The modality `word` names; for auto, the one the scan's values show (segmentation::guessModality).
segmentation::Modality resolveModality(const std::string& word, const Image& scan);

}  // namespace vesalius::cli
