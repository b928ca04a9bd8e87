#include "modality_option.h"

namespace vesalius::cli {

void addModalityOption(CLI::App& command, std::string& word) {
  command
      .add_option("--modality", word,
                  "Scan modality: ct (classes from Hounsfield units: skin, subcutaneous_fat, fat, soft_tissue, "
                  "bone), mri (T1-weighted, classes from the scan's histogram: skin, subcutaneous_fat, dark bone "
                  "such as the skull, soft_tissue) or auto (ct when the scan holds air, values at or below -500, "
                  "else mri)")
      ->check(CLI::IsMember({"auto", "ct", "mri"}))
      ->capture_default_str();
}

segmentation::Modality resolveModality(const std::string& word, const Image& scan) {
  if (word == "ct") return segmentation::Modality::Ct;
  if (word == "mri") return segmentation::Modality::Mri;
  return segmentation::guessModality(scan);
}

}  // namespace vesalius::cli
