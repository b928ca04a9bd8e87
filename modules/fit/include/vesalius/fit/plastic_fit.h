// Plastic-strain fitting of a template tet mesh to markers picked on a scan (Wang, Matcuk, Barbič,
// "Modeling of Personalized Anatomy using Plastic Strains", ACM TOG 40(2), 2021).
//
// Unknowns: a symmetric plastic strain Fp(s) per tet (eq. 2) and the positions x in elastic equilibrium
// under it (eqs. 1, 4). Objective (eq. 6): ½||L s||² + Σ_k c_k/2 ||A_k x + b_k||² over landmarks,
// ICP markers (weight α) and attachments (weight β), with attachments also acting as springs in the
// equilibrium. Gauss-Newton on s (eq. 8) with Z = √c A J from one stiffness factorization per iteration
// (eq. 12), the search direction by the Woodbury identity (eqs. 13-14), plastic eigenvalues clamped to
// 0.01, and Brent's line search on η with the equilibrium re-solved at each η. Stages (§3.4): constant
// s (the initial guess), then attachments, landmarks, ICP markers. Un-attached objects (§3.6) are held by
// the centroid/rotation gauge of rigid_gauge.h and re-aligned rigidly after each iteration (the R, t block
// of the block-coordinate descent).
#pragma once

#include "vesalius/core/mesh.h"
#include "vesalius/core/progress.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace vesalius::fit {

struct FitMarkers {
  MatrixX3d templateLandmarks;    // #L by 3, template (material) points
  MatrixX3d scanLandmarks;        // #L by 3, their positions in the scan, paired by row
  MatrixX3d icp;                  // #I by 3 scan points on the organ's boundary
  MatrixX3d attachmentMaterial;   // #A by 3 template points tied to...
  MatrixX3d attachmentTargets;    // #A by 3 ...these fixed world points (e.g. bone vertices)
};

// Units are mm. The weights multiply squared distances in mm² against the dimensionless smoothness
// ½||L s||²: the paper's α = 1e9 m⁻² and β = 1e8 m⁻² are 1e3 and 1e2 mm⁻².
struct FitOptions {
  double markerWeight = 1e3;      // α: landmarks and ICP markers
  double attachmentWeight = 1e2;  // β: attachments in the objective
  // Attachment springs in the equilibrium: all of them together this many times as stiff as the body
  // (μ · volume^(1/3)); each spring gets an equal share.
  double attachmentStiffness = 10;
  // The elastic baseline's marker springs, each this many times μ · volume^(1/3): hard point constraints
  // as in Wang et al. 2021, Fig. 2.
  double elasticMarkerStiffness = 1e3;
  double poissonRatio = 0.45;
  int constantStrainIterations = 10;
  int landmarkIterations = 20;
  int icpIterations = 20;         // stopping rule (i)
  double maxIcpError = 1.0;       // mm, stopping rule (ii)
  double minStep = 0.01;          // stopping rule (iii): η below this ends a stage
  // Also ends a stage (ours): an iteration that lowers the objective by less than this fraction of the
  // stage's starting value. Without it a stage whose constraints are met exactly (attachments already
  // reached) keeps taking full steps of vanishing size.
  double minDecrease = 1e-6;
  // Ends the ICP stage (ours): the last icpGainIterations iterations together lowered the mean ICP error by
  // less than minIcpGain times its value before them, or by less than minIcpGainMm. Rules (i)-(iii) let a
  // converged fit run on: the OpenSim pelvis on the CT went 0.347 -> 0.344 mm over 15 of its 20 ICP
  // iterations, 15 minutes; the beam of the tests creeps from 0.2 to 0.14 µm by 1-2 % an iteration.
  // 0 turns a threshold off.
  double minIcpGain = 0.01;
  double minIcpGainMm = 0.001;
  int icpGainIterations = 2;
  double eigenvalueFloor = 0.01;  // plastic stretches clamped from below (§3.4)
  int lineSearchEvaluations = 8;  // Brent evaluations per iteration
  // Ours: the line search covers η up to where some tet's plastic parameters change by this fraction of
  // their size, so that a Gauss-Newton step along a direction the constraints hardly feel cannot demand an
  // absurd rest shape.
  double maxStrainChange = 0.5;
};

struct FitIteration {
  std::string stage;   // "constant", "attachments", "landmarks", "icp"
  int iteration = 0;   // within the stage
  double objective = 0, smoothness = 0, constraints = 0;
  double step = 0;     // the accepted η
  double damping = 0;  // λ after the iteration (Levenberg-Marquardt, relative to ||Z||² / trace(D))
  double meanIcpError = 0, maxIcpError = 0;  // mm, at the accepted x (0 without ICP markers)
  double seconds = 0;
};

// Why a stage ended: "iterations" (rule i), "max_icp_error" (ii), "step" (iii), "objective" (minDecrease),
// "icp_gain" (minIcpGain, minIcpGainMm) or "no_descent" (no damping gave a line search that improves).
struct FitStageEnd {
  std::string stage;
  int iterations = 0;
  std::string reason;
};

struct FitResult {
  MatrixX3d V;                   // #V by 3 fitted positions (the template's tets and numbering)
  Eigen::VectorXd s;             // 6#T plastic parameters, tet-major
  Eigen::VectorXd icpErrors;     // #I final marker-to-surface distances, mm
  Eigen::VectorXd landmarkErrors;  // #L final landmark distances, mm
  std::vector<FitIteration> history;
  std::vector<FitStageEnd> stageEnds;  // the stages that ran, in order
  bool attached = false;
};

// templ: the template tet mesh (V in its own frame is the material space, T positively oriented); x0:
// #V by 3 starting positions (the placed template, see initial_placement.h), s0: 6#T starting plastic
// parameters (e.g. the placement's scale times identity). Throws BadInput on an unusable template or
// markers and NumericalFailure when the solver breaks down.
FitResult fitPlasticStrains(const TetMesh& templ, const MatrixX3d& x0, const Eigen::VectorXd& s0,
                            const FitMarkers& markers, const FitOptions& options = {},
                            Progress* progress = nullptr);

// The plain elastic baseline (Wang et al. 2021, Fig. 2 and §3.8, "FEM static solver"): no plastic change, s0 kept;
// landmarks, ICP markers (re-projected until they settle) and attachments are stiff springs. Its spikes
// under point constraints are what the plastic fit avoids.
FitResult fitElastic(const TetMesh& templ, const MatrixX3d& x0, const Eigen::VectorXd& s0, const FitMarkers& markers,
                     const FitOptions& options = {}, Progress* progress = nullptr);

}  // namespace vesalius::fit
