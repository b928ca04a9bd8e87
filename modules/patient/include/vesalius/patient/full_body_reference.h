// The full-body reference of anatomy transfer (Dicko et al. 2013, §3): a MakeHuman skin with an OpenSim model's
// bones and muscle path points placed inside it by the GRAPP 2012 paper's body frame and per-body similarity fits
// (transfer/skeleton_placement.h). `vesalius reference full-body` writes it as a reference folder; the
// virtual patient completes it into a patient's partial skin (reference_completion.h).
//  1. The body frame (transfer/body_frame.h) from the skin and the MakeHuman rig's leg joints; the head-
//     spine joint and the sagittal plane from it.
//  2. The OpenSim bodies placed on the rig (Rajagopal 2016 to MakeHuman's default rig), the digits fitted
//     one by one; each bone mesh a bone tissue whose group is its OpenSim body (the skull and jaw apart:
//     Dicko et al. 2013, §8, gives each trunk bone a map of its own, and one trunk map scaled the skull with a
//     muscular body's chest), trunk bodies (pelvis, torso) symmetric; each muscle path point a point fixed
//     to its body's first mesh, each non-root body's origin a point "joint/BODY".
//  3. Rule R6 for the reference itself: each unit of bones (a symmetric trunk group as one, every other
//     mesh alone) moved inside the skin by the smallest similarity change that keeps the joints near it in
//     place (transfer/bones_inside_skin.h; trunk groups kept symmetric), what is still outside then bent
//     inside (transfer/bones_warped_into_skin.h), the points fixed to its bones with it. "Inside" counts
//     the skin's cavities (meshing/body_distance.h): the skull and jaw need the mouth.
//  4. Given organs and muscles made for this skin (FullBodySources::organs: reference_organs.h, shipped in
//     templates/reference-organs/), each added as it is, of its kind.
#pragma once

#include "vesalius/core/anatomy.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/skeleton.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace vesalius::patient {

// What the reference is made of, read and in mm LPS (the command reads the files).
struct FullBodySources {
  std::string name;                 // the reference's name
  TriMesh skin;                     // the MakeHuman skin, closed, with its uv
  Skeleton rig;                     // MakeHuman's default rig on that skin (upperleg01.L/R, foot.L/R needed)
  MusculoskeletalModel model;       // the OpenSim model: bodies, geometry entries, muscle paths
  std::vector<TriMesh> geometry;    // per model.geometry entry: the mesh in its body's frame, scaled
  std::vector<std::string> geometryNames;  // per entry: the mesh's name (its file's stem), the tissue name
  // Step 4: a reference folder of organs and muscles whose skin is `skin` (`vesalius reference organs`);
  // its organ and muscle tissues are added. None: the reference is bones alone.
  std::optional<ReferenceAnatomy> organs;
  std::string organsSource;  // names it in messages
};

// Step 3's change of one unit of bones.
struct BoneUnitIntoSkin {
  std::string unit;
  long outsideBefore = 0, outsideAfterChange = 0, outsideAfter = 0;  // bone vertices outside the skin
  double bendLargestMm = 0, scale = 1, turnDegrees = 0, centroidShiftMm = 0, jointShiftMm = 0;
  long joints = 0;  // joint centres kept in place
};

struct FullBodyReference {
  ReferenceAnatomy anatomy;
  std::vector<BoneUnitIntoSkin> intoSkin;  // step 3, by unit name
  long outsideBefore = 0, outsideAfter = 0;  // bone vertices outside the skin before and after step 3
  int headSlices = 0;                        // the body frame's head slices
};

// Throws BadInput naming `skeletonSource` if the rig lacks a leg joint, and as the placement does; naming
// `sources.organsSource` if the organs' skin is not `sources.skin` (made for another body).
FullBodyReference buildFullBodyReference(const FullBodySources& sources, const std::string& skeletonSource);

}  // namespace vesalius::patient
