// The colour a tissue mesh of an anatomy directory is drawn in, from its file name: bones ivory, muscles
// red, any other tissue (an organ) one of a few distinct colours picked by its name, so a tissue keeps
// its colour from run to run. Names are TotalSegmentator's labels (femur_left, gluteus_maximus_right, ...)
// or free names containing "bone" or "muscle" (VHF_Left_Muscle_GluteusMaximus).
#pragma once

#include <Eigen/Core>

#include <string>

namespace vesalius::poser {

// RGB in [0, 1] for the mesh named `stem` (file name without its extension).
Eigen::Vector3d tissueColour(const std::string& stem);

}  // namespace vesalius::poser
