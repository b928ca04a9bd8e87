// The anatomy a labelled scan (CT or MRI) shows by itself (Dicko et al. 2013, §3, Fig. 2.c): the body's outer surface as the skin,
// and every label of an organ/bone segmentation (TotalSegmentator's names, v1 or v2) as a closed tissue
// surface of its kind. The torso reference of anatomy transfer (`vesalius reference torso`) and the
// virtual patient's own anatomy inside the field of view (virtual_patient.h) are both this.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/grid.h"
#include "vesalius/core/label_map.h"
#include "vesalius/core/progress.h"
#include "vesalius/segmentation/scan_modality.h"

#include <string>
#include <vector>

namespace vesalius::patient {

// Kind, bone group and symmetry of a TotalSegmentator label name, as Dicko et al. 2013, §8, moves bones: the trunk
// (spine, sternum, pelvis, rib cage, skull) symmetrically, each vertebra (or the MR labels' one "vertebrae")
// a group of its own, the ribs and sternum the rib cage, hips and sacrum the pelvis; paired limb bones
// freely; gluteal, iliopsoas and back muscles are muscles; every other label an organ. Sets tissue.kind,
// .group, .symmetric from tissue.name.
void classifyTissue(ReferenceTissue& tissue);

// The sagittal plane from the tissues that come in left/right pairs (names with "left" / "right"): its
// normal the mean direction from each right part's centroid to its left partner's, through the mean of
// their midpoints. Throws BadInput naming `source` if no pair is found.
Plane sagittalPlaneOfPairs(const std::vector<ReferenceTissue>& tissues, const std::string& source);

// Skin vertices on the caps where the scan's field of view cut the body: beyond the centre of the first or
// last slice along an axis at whose end `body` (the body mask the skin was made from) has voxels. A mask
// touching the volume's end is closed half a voxel past it; those caps are the scan's edge, not skin.
// Ascending indices into skin.V.
std::vector<int> scanCutVertices(const TriMesh& skin, const Grid<std::uint8_t>& body);

struct ScanAnatomyOptions {
  // How the body is told from the air around it: by Hounsfield units (a CT) or by the scan's histogram (an
  // MRI; segmentation/scan_modality.h).
  segmentation::Modality modality = segmentation::Modality::Ct;
  int skinFaces = 20000;   // triangles of the skin surface
  int tissueFaces = 3000;  // triangles of each tissue surface
};

// The skin (the body mask's surface, mm LPS, with its cut vertices) of `scan`; throws BadInput naming
// `source` if the scan holds no body.
TriMesh scanSkin(const Image& scan, const ScanAnatomyOptions& options, const std::string& source,
                 std::vector<int>& cutVertices);

// scan: a CT in HU or an MRI (options.modality); labels: its organ/bone segmentation on the same grid
// (BadInput naming labelsSource otherwise). The skin as scanSkin, every label in the table with voxels as a
// tissue (classifyTissue), the sagittal plane from the left/right pairs.
ReferenceAnatomy scanAnatomy(const Image& scan, const LabelMap& labels, const ScanAnatomyOptions& options,
                             const std::string& scanSource, const std::string& labelsSource,
                             Progress* progress = nullptr);

}  // namespace vesalius::patient
