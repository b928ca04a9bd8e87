// The label table of the CT tissue classes (ct_tissues.h).
#include "vesalius/segmentation/ct_tissues.h"

namespace vesalius::segmentation {

LabelTable ctTissueTable(bool splitBone) {
  // Skin, fat, muscle and bone take the colours of 3D Slicer's GenericAnatomyColors, so overlays look
  // familiar; fat other than subcutaneous is set apart in orange.
  LabelTable table;
  table.add({kCtSkin, "skin", {{177, 122, 101}}});
  table.add({kCtSubcutaneousFat, "subcutaneous_fat", {{230, 220, 70}}});
  table.add({kCtFat, "fat", {{255, 150, 40}}});
  table.add({kCtSoftTissue, "soft_tissue", {{192, 104, 88}}});
  if (splitBone) {
    table.add({kCtBone, "cortical_bone", {{241, 214, 145}}});
    table.add({kCtTrabecularBone, "trabecular_bone", {{212, 188, 102}}});
  } else {
    table.add({kCtBone, "bone", {{241, 214, 145}}});
  }
  return table;
}

}  // namespace vesalius::segmentation
