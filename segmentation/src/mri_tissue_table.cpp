// The label table of the MRI tissue classes (mri_tissues.h).
#include "vesalius/segmentation/ct_tissues.h"
#include "vesalius/segmentation/mri_tissues.h"

namespace vesalius::segmentation {

LabelTable mriTissueTable() {
  // The same names and colours as the CT classes, so tools and overlays treat both alike.
  const LabelTable ct = ctTissueTable(false);
  LabelTable table;
  for (auto [id, ctId] : {std::pair{kMriSkin, kCtSkin}, std::pair{kMriSubcutaneousFat, kCtSubcutaneousFat},
                          std::pair{kMriBone, kCtBone}, std::pair{kMriSoftTissue, kCtSoftTissue}}) {
    LabelEntry entry = *ct.find(Label(ctId));
    entry.id = id;
    table.add(entry);
  }
  return table;
}

}  // namespace vesalius::segmentation
