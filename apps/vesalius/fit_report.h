// What `vesalius fit` tells of a template fit (fit/template_fit.h): the metrics of its report, the summary it
// prints and its picture.
#pragma once

#include "vesalius/core/grid.h"
#include "vesalius/fit/template_fit.h"
#include "vesalius/io/report.h"
#include "vesalius/viz/rgb_image.h"

#include <string>

namespace vesalius::cli {

// The metrics: what Wang et al. 2021 plots (per-marker errors and their histogram, Fig. 16; the objective per
// iteration, Fig. 9; the minimum dihedral angles before and after, Fig. 17), the placement, the rounds.
void reportFit(const fit::TemplateFit& f, io::Report& report);

// The lines on standard output: what was fitted to what, how it was placed, the errors before and after.
// out: the fitted mesh's path; method: "plastic" or "elastic"; seconds: the command's wall time.
void printFitSummary(const std::string& out, const std::string& method, const fit::TemplateFit& f, double seconds);

// The fitted surface's outline over three slices of `scan` through the markers (Wang et al. 2021, Fig. 18), beside the
// histogram of the ICP errors after the fit (Fig. 16). window, level: grey mapping of the scan, scan units.
viz::RgbImage fitPicture(const Image& scan, const fit::TemplateFit& f, double window, double level);

}  // namespace vesalius::cli
