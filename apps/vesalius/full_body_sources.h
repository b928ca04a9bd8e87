// The files of the full-body reference (patient/full_body_reference.h) read into its sources, in mm LPS:
// a MakeHuman skin (decimetres, +Y up; its uv from base.obj if it has none), MakeHuman's default rig and
// an OpenSim model with its Geometry folder beside it, and the organs made for that skin (a reference
// folder, templates/reference-organs/). Shared by `reference full-body`, `reference organs` and `patient`,
// as is the organ template library (readOrganTemplates).
#pragma once

#include "vesalius/patient/full_body_reference.h"
#include "vesalius/patient/virtual_patient.h"

#include <string>
#include <vector>

namespace vesalius::cli {

// baseMesh: MakeHuman's base.obj for the rig and the skin's uv; empty for the one beside the rig. organs:
// a reference folder of organs and muscles made for `skin`; empty for none. Throws BadInput naming the
// file that cannot be read.
patient::FullBodySources readFullBodySources(const std::string& skin, const std::string& skeleton,
                                             const std::string& baseMesh, const std::string& model,
                                             const std::string& organs = "");

// The organ template library: every <organ>.obj (.stl .ply .vtp) of the folder, the organ named by the
// file's stem, sorted by name. Throws BadInput naming a folder that is not one.
std::vector<patient::OrganTemplate> readOrganTemplates(const std::string& folder);

// The shipped sources of the full-body reference (shipped_data.h): MakeHuman's neutral body and default
// rig, OpenSim's Rajagopal et al. 2016 model; `reference full-body`'s defaults.
struct FullBodyFiles {
  std::string skin, skeleton, model;
};
FullBodyFiles shippedFullBodyFiles();

// The full-body reference built from the shipped sources and, with organs, the organs and muscles made
// for that body (templates/reference-organs/), as `vesalius reference full-body` builds it.
ReferenceAnatomy shippedFullBodyReference(bool withOrgans);

}  // namespace vesalius::cli
