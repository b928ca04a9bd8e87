// vesalius fit as a function, so that other commands can run it (the demo fits the shipped liver).
#pragma once

#include "common.h"

#include "vesalius/fit/plastic_fit.h"
#include "vesalius/fit/refit.h"

#include <Eigen/Core>

#include <string>

namespace vesalius::cli {

struct FitCommandOptions {
  std::string templ, icp, templateLandmarks, scanLandmarks, attachTo, attachments;
  std::string out, surfaceOut, embed, embedOut, overlay, png;
  double attachRadius = 0;
  bool unattached = false;
  std::string method = "plastic", init = "similarity";
  long targetTets = 20000;
  int templateFaces = 0;  // coarsen a surface template to this many triangles first; 0: as targetTets allows
  double window = 400, level = 40;
  fit::FitOptions solver;
  fit::RefitOptions refit;  // refits: 0 is seed 002's fit alone
  CommonOptions common;
};

struct FitOutcome {
  long tets = 0;  // of the last round's mesh (the template's unless refitted)
  Eigen::VectorXd icpBefore, icpAfter;  // #icp marker distances to the surface, mm
  double seconds = 0;
};

// Runs the whole command: reads, places, fits, writes the outputs, prints the summary, writes the report.
FitOutcome runFit(const FitCommandOptions& o);

}  // namespace vesalius::cli
