// A template organ fitted to markers picked on a scan, the whole job of `vesalius fit` (Wang, Matcuk,
// Barbič, "Modeling of Personalized Anatomy using Plastic Strains", ACM TOG 40(2), 2021):
//
// 1. A surface template is tetrahedralized (meshing/template_tets.h: closed by its winding number first if
//    it is not a closed 2-manifold, decimated as the tet target allows); a tet template is used as it is.
// 2. The markers are taken from their sets (§3.1): ICP markers, every defined point of the ICP set that is
//    of that kind; landmarks paired by label between a template set and a scan set, or scan landmarks that
//    carry their template points (core/markers.h templatePosition); attachments that carry theirs (§3.3).
// 3. The template is placed by a similarity (Fig. 1 starts from a rigidly aligned template; ours also
//    scales it, initial_placement.h), or left where it is. An organ held by a bone gets attachments from the
//    bone vertices near the placed template (§4.1.2, attachments.h); an attached organ needs three (§3.3:
//    they must remove its rigid motions). Without attachments it is free (§3.6).
// 4. The plastic fit (plastic_fit.h), or the elastic baseline of Fig. 2; then, for the plastic fit, refits
//    from the fitted shape tetrahedralized afresh at the same target (ours, refit.h).
// 5. The fitted tets (with each tet's smallest and largest plastic stretch), the fitted surface (a surface
//    template's own triangles carried by the fit; after refits the last round's boundary, which the
//    template's triangles follow only as closely as they are fine), a surface embedded in the template
//    carried through every round (§4.3), and the measures the paper plots: per-marker errors and their
//    histogram (Fig. 16), the objective per iteration (Fig. 9), the minimum dihedral angles before and
//    after (Fig. 17).
//
// Reads and writes nothing: the caller reads the files and names them (`source`) for messages.
#pragma once

#include "vesalius/core/markers.h"
#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"
#include "vesalius/fit/initial_placement.h"
#include "vesalius/fit/plastic_fit.h"
#include "vesalius/fit/refit.h"
#include "vesalius/meshing/template_tets.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace vesalius::fit {

constexpr double kIcpErrorBinMm = 0.25;  // bins of the ICP error histogram (Fig. 16)
constexpr double kDihedralBinDeg = 5.0;  // bins of the minimum dihedral angle histograms (Fig. 17)

enum class FitMethod { Plastic, Elastic };

struct TemplateFitOptions {
  FitMethod method = FitMethod::Plastic;  // Elastic: the FEM baseline of Fig. 2, no plastic strains
  bool placeBySimilarity = true;          // false: the template stays where it is
  double attachRadius = 0;                // mm: bone vertices this close to the placed template are attached
  // A surface template's tets and each refit's: about targetTets (within twice it), or at templateFaces
  // triangles when positive.
  meshing::TemplateTetsOptions tets;
  FitOptions solver;
  RefitOptions refit;  // refits = 0: Wang et al.'s fit alone; refits need the plastic fit (UsageError)
};

// A marker set and the name of where it came from, for messages.
struct SourcedMarkers {
  MarkerSet set;
  std::string source;
};

struct TemplateFitInputs {
  // The template in its own (template) space, mm: exactly one of a tet mesh and a surface (UsageError).
  std::optional<TetMesh> templateTets;
  std::optional<TriMesh> templateSurface;
  std::string templateSource = "template";
  SourcedMarkers icp;  // its defined ICP markers (BadInput naming the source if there are none)
  // Landmarks: both sets (paired by label), the scan's alone (each carrying its template position), or none.
  std::optional<SourcedMarkers> templateLandmarks, scanLandmarks;
  // How the organ is held: attachments (each carrying its template position), a bone surface (world mm;
  // needs options.attachRadius > 0), or neither (free). Both: UsageError.
  std::optional<SourcedMarkers> attachments;
  std::optional<TriMesh> bone;
  std::string boneSource = "bone";
  std::optional<TriMesh> embed;  // a surface in template space to carry along
  std::string fittedName = "fitted";  // names the fitted shape when a refit cannot tetrahedralize it
};

struct Quantiles {
  double min = 0, p05 = 0, median = 0, p95 = 0, max = 0;
};

struct MinDihedrals {
  double minDeg = 0;            // smallest over the tets
  std::vector<long> histogram;  // of each tet's smallest angle, kDihedralBinDeg bins
};

struct RoundMeasures {
  double minDihedralDeg = 0;   // of the round's fitted tets
  Quantiles plasticStretches;  // of the round's Fp (against the round's rest shape)
};

struct TemplateFit {
  // The template
  TetMesh templ;  // the tets fitted first: V #V by 3 in template space, T #T by 4
  std::optional<meshing::SurfaceRepair> repair;  // a surface template that had to be closed
  long tetrahedralizedFaces = 0;                 // of a surface template: triangles TetGen was given
  // The markers
  FitMarkers markers;  // as fitted; attachments from the bone included
  std::vector<std::string> icpLabels, landmarkLabels;  // per row of markers.icp and markers.scanLandmarks
  long skippedMarkers = 0;  // not defined, and points of another kind in the ICP set
  // The placement
  Placement placement;
  std::string placedFrom;  // "landmarks", "icp markers" or "none"
  MatrixX3d placedV;       // #V by 3 the placed template
  bool attachedToClosedBone = false;  // every bone vertex within the radius holds it, also away from its insertion
  // The fit
  std::vector<FitRound> rounds;     // the first fit, then each refit kept
  TetMesh fitted;                   // the last round's tets at their fitted positions, with tet fields
                                    // plastic_stretch_min and plastic_stretch_max (its Fp's eigenvalues)
  TriMesh surface;                  // the fitted surface
  std::optional<TriMesh> embedded;  // inputs.embed carried through every round
  // The measures (mm, mm^3, degrees)
  Eigen::VectorXd icpBefore;         // #I marker-to-surface distances of the placed template
  Eigen::VectorXd landmarksBefore;   // #L landmark distances of the placed template
  Eigen::VectorXd attachmentErrors;  // #A attachment distances after the fit
  std::vector<long> icpErrorHistogram;  // of the last round's ICP errors, kIcpErrorBinMm bins
  MinDihedrals dihedralsBefore, dihedralsAfter;  // of the placed template and of the last round's tets
  std::vector<RoundMeasures> roundMeasures;      // per round
  Quantiles plasticStretches;  // the first round's Fp, against the template
  double templateVolume = 0, placedVolume = 0, fittedVolume = 0;
  long invertedAfter = 0;  // fitted tets of non-positive volume
  // Wall time of "tetrahedralize" (a surface template), "placement" and "fit", in that order.
  std::vector<std::pair<std::string, double>> stageSeconds;
};

// Throws BadInput naming the source for an unusable template (flat, cannot be closed or tetrahedralized),
// markers (no ICP markers; landmarks that do not pair; a landmark or attachment without its template
// position; fewer than 3 attachments) or bone; UsageError for inputs or options that contradict each
// other; what fitPlasticStrains and fitElastic throw.
TemplateFit fitTemplate(const TemplateFitInputs& inputs, const TemplateFitOptions& options = {},
                        Progress* progress = nullptr);

}  // namespace vesalius::fit
