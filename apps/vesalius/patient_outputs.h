// What `vesalius patient` writes into its output folder (docs/virtual-patient.md, docs/cli.md): the whole
// model and the part inside the scan, the scan's skin with its fat, the tissue classes, the rig, each fitted
// organ's markers and carried template, the posed patient, and report.json's metrics.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/io/report.h"
#include "vesalius/patient/patient_rig.h"
#include "vesalius/patient/virtual_patient.h"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace vesalius::cli {

// A pose of the patient and how it was asked for.
struct PatientPose {
  std::vector<Eigen::Isometry3d> world;  // posed world transforms of the rig's joints
  patient::PosedPatient posed;
  std::string method;          // the skinning: lbs, dqs, cor or fem
  std::string angles, motion;  // --pose's joint angles, or --motion's file and its frame
  int frame = 0;
};

// Everything into `dir` (a fresh staging folder), the metrics into `report`, then report.json. pose: null
// for no pose. png: also the pictures (needs a display).
void writePatientFolder(const Image& scan, const patient::VirtualPatient& p, const PatientPose* pose, bool png,
                        const std::string& dir, io::Report& report);

}  // namespace vesalius::cli
