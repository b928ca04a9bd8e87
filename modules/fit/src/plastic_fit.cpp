// The Gauss-Newton driver of Wang et al. 2021, §3.4-3.6. One iteration:
//   1. the stage's constraints at x (ICP markers re-projected onto the surface),
//   2. K and G at (x, s), factored once: Z = √c A J (equilibrium_jacobian.h),
//   3. the search direction from (L² + ZᵀZ) Δs = −(L² s + Zᵀ r) by Woodbury (or, for the constant-s
//      initial guess, the 6-parameter version of the same system),
//   4. Brent's line search on η, each trial re-solving the equilibrium from the linear prediction
//      x + η J Δs, with the plastic eigenvalues clamped,
//   5. for un-attached objects, the rigid re-alignment to the markers.
#include "vesalius/fit/plastic_fit.h"

#include "vesalius/fit/brent_minimize.h"
#include "vesalius/fit/compressed_constraints.h"
#include "vesalius/fit/equilibrium_jacobian.h"
#include "vesalius/fit/plastic_laplacian.h"
#include "vesalius/fit/point_constraints.h"
#include "vesalius/fit/rigid_gauge.h"
#include "vesalius/linalg/similarity_transform.h"
#include "vesalius/fit/surface_projection.h"
#include "vesalius/fit/woodbury.h"

#include "vesalius/fem/plastic_fem.h"
#include "vesalius/fem/plastic_strain.h"
#include "vesalius/fem/point_springs.h"
#include "vesalius/linalg/sparse_cholesky.h"
#include "vesalius/fem/static_equilibrium.h"

#include "vesalius/core/error.h"
#include "vesalius/core/reuse_freed_memory.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace vesalius::fit {
namespace {

enum class Markers { None, Landmarks, Icp };

struct Stage {
  const char* name;
  Markers markers;
  bool constantStrain;
  int maxIterations;
};

// All attachments together about as stiff as the body (times `relative`): k = relative · μ · L / #A with
// L = (template volume)^(1/3). Much stiffer springs would hold their points whatever the plastic
// strain does, and β E_a could no longer see an absurd rest shape (§3.3: E_a measures the work the
// attachments do against the body).
double attachmentSpringStiffness(const PlasticFem& fem, double relative, Eigen::Index attachments) {
  if (attachments == 0) return 0.0;
  return relative * fem.material().mu * std::cbrt(fem.restVolumes().sum()) / double(attachments);
}

// The largest change of a tet's plastic parameters relative to their size: max_t ‖Δs_t‖∞ / ‖s_t‖∞.
double relativeChange(const Eigen::VectorXd& s, const Eigen::VectorXd& ds) {
  double largest = 0;
  for (Eigen::Index t = 0; t < s.size() / 6; ++t)
    largest = std::max(largest, ds.segment<6>(6 * t).cwiseAbs().maxCoeff() / s.segment<6>(6 * t).cwiseAbs().maxCoeff());
  return largest;
}

// The fit runs in a material space scaled by c = (volume-weighted mean det Fp(s0))^(1/3), where the
// starting plastic strains are about I. The smoothness ½||L s||² and the eigenvalue floor are absolute
// in s, so a template in other units (the SOFA liver is in units of about 35 mm) or scaled by its
// placement would otherwise weigh smoothness by c² against the markers and floor the stretches at 0.01 c.
double materialScale(const TetMesh& templ, const Eigen::VectorXd& s0) {
  if (s0.size() != 6 * templ.T.rows()) throw UsageError("fit: starting plastic parameters do not match the template");
  const Eigen::VectorXd V0 = tetVolumes(templ.V, templ.T);
  double placed = 0;
  for (Eigen::Index t = 0; t < templ.T.rows(); ++t)
    placed += V0[t] * plasticStrainMatrix(s0.segment<6>(6 * t)).determinant();
  const double c = std::cbrt(placed / V0.sum());
  if (!(c > 0) || !std::isfinite(c)) throw BadInput("", "fit: the starting plastic strains have no positive volume");
  return c;
}

// [top; bottom], both with the same columns.
Eigen::SparseMatrix<double> stacked(const Eigen::SparseMatrix<double>& top, const Eigen::SparseMatrix<double>& bottom) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(std::size_t(top.nonZeros() + bottom.nonZeros()));
  for (const auto* part : {&top, &bottom})
    for (Eigen::Index j = 0; j < part->outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(*part, j); it; ++it)
        entries.emplace_back(int(it.row() + (part == &bottom ? top.rows() : 0)), int(it.col()), it.value());
  Eigen::SparseMatrix<double> out(top.rows() + bottom.rows(), top.cols());
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

class Fitter {
 public:
  Fitter(const TetMesh& templ, const MatrixX3d& x0, const Eigen::VectorXd& s0, const FitMarkers& markers,
         const FitOptions& options);
  FitResult run(Progress* progress);
  FitResult runElastic(Progress* progress);

 private:
  std::vector<PointConstraint> constraints(Markers which, const Eigen::VectorXd& x) const;
  double smoothness(const Eigen::VectorXd& s) const { return 0.5 * applyPlasticLaplacian(Lsc_, s).squaredNorm(); }
  double objective(Markers which, const Eigen::VectorXd& s, const Eigen::VectorXd& x) const;
  Eigen::VectorXd clamped(Eigen::VectorXd s) const;
  Eigen::VectorXd equilibrium(const Eigen::VectorXd& s, const Eigen::VectorXd& start, const RigidGauge* gauge) const;
  Eigen::SparseMatrix<double> stiffness(bool projected) const;
  struct Linearization;
  struct Trial {
    double eta, f;
    Eigen::VectorXd s, x;
  };
  static constexpr int kDampingAttempts = 8;
  static constexpr double kMinDamping = 1e-9, kStartDamping = 1e-3, kMaxDamping = 1e12;

  Linearization linearize(const Stage& stage);
  Eigen::VectorXd direction(const Stage& stage, Linearization& lin, double mu, bool refined = true) const;
  Eigen::VectorXd boundedDirection(const Stage& stage, Linearization& lin);
  Eigen::VectorXd firstDirection(const Stage& stage, Linearization& lin);
  Eigen::VectorXd field(const Stage& stage, const Eigen::VectorXd& d) const;
  double longestStep(const Stage& stage, const Eigen::VectorXd& d) const;
  double model(const Stage& stage, const Linearization& lin, const Eigen::VectorXd& d, double eta) const;
  std::optional<Trial> lineSearch(const Stage& stage, const Linearization& lin, const Eigen::VectorXd& d);
  std::optional<FitIteration> iterate(const Stage& stage);
  void realign(Markers which);
  void recordErrors(FitIteration& record) const;
  const char* stopReason(const Stage& stage, const std::vector<FitIteration>& history, double decrease,
                         double stageStart) const;
  FitResult result(std::vector<FitIteration> history) const;

  const double scale_;  // c: the material space is the template's times c, s is Fp / c
  const MatrixX3d restV_;
  const MatrixX4i T_;
  const FitMarkers markers_;
  const FitOptions options_;
  PlasticFem fem_;
  PointSprings springs_;
  std::vector<PointConstraint> attachments_, landmarks_;
  CompressedConstraints attachmentRows_;  // the attachments' terms of the objective, as few rows
  SurfaceProjection surface_;
  Eigen::SparseMatrix<double> Lsc_;
  SmoothnessBaseSolver base_;
  Eigen::SparseMatrix<double> constantMap_;  // 6#T by 6: the same Fp in every tet
  mutable SparseCholesky cholesky_;
  double springStiffness_;
  Eigen::VectorXd x_, s_;
  bool attached_;
  double damping_ = kStartDamping;  // λ of the Levenberg-Marquardt damping
};

Fitter::Fitter(const TetMesh& templ, const MatrixX3d& x0, const Eigen::VectorXd& s0, const FitMarkers& markers,
               const FitOptions& options)
    : scale_(materialScale(templ, s0)), restV_(scale_ * templ.V), T_(templ.T), markers_(markers),
      options_(options), fem_(restV_, templ.T, StableNeoHookean::fromYoungPoisson(1.0, options.poissonRatio)),
      surface_(templ.T), Lsc_(tetAdjacencyLaplacian(templ.T)), base_(Lsc_),
      springStiffness_(attachmentSpringStiffness(fem_, options.attachmentStiffness, markers.attachmentMaterial.rows())),
      x_(PlasticFem::flatten(x0)), s_(s0 / scale_), attached_(markers.attachmentMaterial.rows() > 0) {
  reuseFreedMemory();  // every iteration allocates and frees Wᵀ and the Woodbury blocks, about 100 MB each
  if (x0.rows() != templ.V.rows()) throw UsageError("fit: starting positions do not match the template");
  // Un-attached, the landmark stage's 3 rows per pair, less the 6 rigid motions the gauge takes, must fix
  // the 6 constant plastic strains that ½||L s||² leaves free.
  if (!attached_ && markers.scanLandmarks.rows() > 0 && markers.scanLandmarks.rows() < 4)
    throw UsageError("fit: an un-attached organ needs at least 4 landmark pairs, or none (" +
                     std::to_string(markers.scanLandmarks.rows()) + " cannot fix its plastic strain)");
  if (attached_) {
    attachments_ = embedMaterialPoints(restV_, templ.T, scale_ * markers.attachmentMaterial, markers.attachmentTargets,
                                       options.attachmentWeight);
    springs_ = asSprings(attachments_, springStiffness_);
  }
  attachmentRows_ = compressConstraints(attachments_, restV_.rows());
  landmarks_ = embedMaterialPoints(restV_, templ.T, scale_ * markers.templateLandmarks, markers.scanLandmarks,
                                   options.markerWeight);
  std::vector<Eigen::Triplet<double>> e;
  for (Eigen::Index t = 0; t < T_.rows(); ++t)
    for (int k = 0; k < 6; ++k) e.emplace_back(int(6 * t + k), k, 1.0);
  constantMap_.resize(6 * T_.rows(), 6);
  constantMap_.setFromTriplets(e.begin(), e.end());
}

std::vector<PointConstraint> Fitter::constraints(Markers which, const Eigen::VectorXd& x) const {
  std::vector<PointConstraint> all;
  if (which == Markers::Landmarks) all.insert(all.end(), landmarks_.begin(), landmarks_.end());
  if (which == Markers::Icp) {
    const auto icp = surface_.closestPoints(x, markers_.icp, options_.markerWeight);
    all.insert(all.end(), icp.begin(), icp.end());
  }
  return all;
}

double Fitter::objective(Markers which, const Eigen::VectorXd& s, const Eigen::VectorXd& x) const {
  return smoothness(s) + 0.5 * constraintResiduals(constraints(which, x), x).squaredNorm() + attachmentRows_.energy(x);
}

Eigen::VectorXd Fitter::clamped(Eigen::VectorXd s) const {
  for (Eigen::Index t = 0; t < T_.rows(); ++t)
    s.segment<6>(6 * t) = clampPlasticStrain(s.segment<6>(6 * t), options_.eigenvalueFloor);
  return s;
}

Eigen::VectorXd Fitter::equilibrium(const Eigen::VectorXd& s, const Eigen::VectorXd& start,
                                    const RigidGauge* gauge) const {
  const EquilibriumResult r = solveStaticEquilibrium(fem_, s, springs_, start, EquilibriumOptions{});
  if (!r.converged) throw NumericalFailure("fit: the elastic equilibrium did not converge");
  if (!(fem_.elasticJacobians(r.x, s).minCoeff() > 0))
    throw NumericalFailure("fit: the elastic equilibrium inverts a tet");
  return gauge ? gauge->impose(r.x) : r.x;
}

Eigen::SparseMatrix<double> Fitter::stiffness(bool projected) const {
  Eigen::SparseMatrix<double> K = fem_.stiffness(x_, s_, projected);
  if (attached_) K += pointSpringHessian(springs_, T_, int(restV_.rows()));
  return K;
}

// What one Gauss-Newton iteration linearises at (x_, s_).
struct Fitter::Linearization {
  std::vector<PointConstraint> active;
  std::unique_ptr<RigidGauge> gauge;
  std::unique_ptr<EquilibriumJacobian> J;
  // √c A J, in the stage's parameters; the attachments' rows first. Full-field stages hand it over to
  // the Woodbury solver.
  std::optional<ConstraintJacobian> Z;
  Eigen::VectorXd r;              // √c (A x + b), the same rows
  Eigen::VectorXd gradient;       // of the objective in the stage's parameters: L² s + Zᵀ r (projected)
  std::unique_ptr<WoodburySolver> woodbury;  // full-field stages
  double dampingScale = 1.0;      // ||Z||² / trace(D): μ = λ · this
  double f0 = 0.0;
  const ConstraintJacobian& constraintJacobian() const { return woodbury ? woodbury->Z() : *Z; }
};

Fitter::Linearization Fitter::linearize(const Stage& stage) {
  Linearization lin;
  lin.active = constraints(stage.markers, x_);
  if (!attached_) lin.gauge = std::make_unique<RigidGauge>(lin.active, restV_, x_);
  Eigen::SparseMatrix<double> G = fem_.plasticForceJacobian(x_, s_);
  if (stage.constantStrain) G = G * constantMap_;
  try {
    lin.J = std::make_unique<EquilibriumJacobian>(stiffness(false), G, x_, lin.gauge.get(), cholesky_);
  } catch (const NumericalFailure&) {
    // An equilibrium next to a buckling is not definite; the projected stiffness still gives a descent.
    lin.J = std::make_unique<EquilibriumJacobian>(stiffness(true), G, x_, lin.gauge.get(), cholesky_);
  }
  lin.Z.emplace(lin.J->constraintJacobian(stacked(attachmentRows_.rows, constraintRows(lin.active, restV_.rows()))));
  const Eigen::VectorXd held = attachmentRows_.residuals(x_), marked = constraintResiduals(lin.active, x_);
  lin.r.resize(held.size() + marked.size());
  lin.r << held, marked;
  const Eigen::VectorXd smoothGradient = applyPlasticLaplacian(Lsc_, applyPlasticLaplacian(Lsc_, s_));
  if (stage.constantStrain) {
    lin.gradient = lin.Z->transposeTimes(lin.r) + constantMap_.transpose() * smoothGradient;
    lin.dampingScale = lin.Z->squaredNorm() / 6.0;  // D restricted to constant fields is #T · I
  } else {
    lin.gradient = smoothGradient + lin.Z->transposeTimes(lin.r);
    lin.dampingScale = lin.Z->squaredNorm() / (9.0 * Lsc_.squaredNorm() + 6.0);  // trace(D) = Σ ξ² ||Lsc||² + 6
  }
  lin.dampingScale = std::max(lin.dampingScale, 1e-12);
  if (!stage.constantStrain) {  // factored once, at the damping of its first direction
    lin.woodbury = std::make_unique<WoodburySolver>(base_, std::move(*lin.Z), damping_ * lin.dampingScale);
    lin.Z.reset();
  }
  lin.f0 = objective(stage.markers, s_, x_);
  return lin;
}

// The damped Gauss-Newton direction in the stage's parameters: (H + μ D) d = −gradient.
Eigen::VectorXd Fitter::direction(const Stage& stage, Linearization& lin, double mu, bool refined) const {
  if (stage.constantStrain) {
    const Eigen::MatrixXd Z = *lin.Z * Eigen::MatrixXd::Identity(6, 6);
    Eigen::Matrix<double, 6, 6> H = Z.transpose() * Z;
    H.diagonal().array() += mu * double(T_.rows());
    return H.ldlt().solve(-lin.gradient);
  }
  lin.woodbury->setDamping(mu);
  const Eigen::MatrixXd h = -lin.gradient;
  return (refined ? lin.woodbury->solve(h) : lin.woodbury->solveUnrefined(h)).col(0);
}

// The damped direction with λ raised (and kept) until its full step changes no tet's plastic parameters by more
// than maxStrainChange of their size: a trust region on Fp. The undamped Gauss-Newton step of a template
// far from its markers asks for stretches of several hundred percent in a few tets, where neither the
// linear model nor the equilibrium solve can follow; the damped one is smoother (D ⊇ L²) and shorter.
// The trials are measured unrefined; only the one kept is refined.
Eigen::VectorXd Fitter::boundedDirection(const Stage& stage, Linearization& lin) {
  for (;;) {
    Eigen::VectorXd d = direction(stage, lin, damping_ * lin.dampingScale, false);
    const double change = relativeChange(s_, field(stage, d));
    if (change <= options_.maxStrainChange || damping_ >= kMaxDamping)
      return stage.constantStrain ? d : Eigen::VectorXd(lin.woodbury->refine(-lin.gradient, d).col(0));
    damping_ *= std::max(2.0, change / options_.maxStrainChange);
  }
}

// A stage's direction as a change of all 6#T plastic parameters.
Eigen::VectorXd Fitter::field(const Stage& stage, const Eigen::VectorXd& d) const {
  return stage.constantStrain ? Eigen::VectorXd(constantMap_ * d) : d;
}

// The strain-change bound on η along d, at most 1.
double Fitter::longestStep(const Stage& stage, const Eigen::VectorXd& d) const {
  return std::min(1.0, options_.maxStrainChange / relativeChange(s_, field(stage, d)));
}

// The objective the linearization predicts at s + η d.
double Fitter::model(const Stage& stage, const Linearization& lin, const Eigen::VectorXd& d, double eta) const {
  const Eigen::VectorXd ds = field(stage, d);
  return 0.5 * (lin.r + eta * (lin.constraintJacobian() * d)).squaredNorm() + attachmentRows_.offset +
         smoothness(s_ + eta * ds);
}

// The first direction tried. ICP markers are re-projected onto the surface as it moves, so their linear
// model holds only near x: the damped direction that meets the strain bound at full length (a trust
// region) takes the SOFA liver to 2.1 mm mean marker error on the CT, where Gauss-Newton stalls at 5.7. Landmarks
// and attachments keep their material points, and thin parts that must stretch several-fold (the string
// of Fig. 23) need the Gauss-Newton direction, shortened to the bound by the line search.
Eigen::VectorXd Fitter::firstDirection(const Stage& stage, Linearization& lin) {
  if (stage.markers == Markers::Icp) return boundedDirection(stage, lin);
  return direction(stage, lin, damping_ * lin.dampingScale);
}

// Brent's line search along d (§3.4), each trial re-solving the equilibrium. The full step (shortened
// so that no plastic parameter changes by more than maxStrainChange) is tried first and kept when it
// realises at least half the decrease the linear model predicts. Nothing if no trial improves.
std::optional<Fitter::Trial> Fitter::lineSearch(const Stage& stage, const Linearization& lin,
                                                const Eigen::VectorXd& d) {
  const Eigen::VectorXd ds = field(stage, d);
  const Eigen::VectorXd predicted = lin.J->apply(d);
  std::optional<Trial> best;
  const auto trial = [&](double eta) {
    if (eta <= 0.0) return lin.f0;
    try {
      Eigen::VectorXd s = clamped(s_ + eta * ds);
      // The linear prediction is the better start unless it inverts a tet; x_ never does (det Fp > 0).
      Eigen::VectorXd start = x_ + eta * predicted;
      if (fem_.elasticJacobians(start, s).minCoeff() <= 0) start = x_;
      Eigen::VectorXd x = equilibrium(s, start, lin.gauge.get());
      const double f = objective(stage.markers, s, x);
      if (f < lin.f0 && (!best || f < best->f)) best = Trial{eta, f, std::move(s), std::move(x)};
      return f;
    } catch (const NumericalFailure&) {
      return std::numeric_limits<double>::max();
    }
  };
  const double etaMax = longestStep(stage, d);
  const double f1 = trial(etaMax);
  if (!(lin.f0 - f1 >= 0.5 * (lin.f0 - model(stage, lin, d, etaMax))))
    minimizeBrent(trial, 0.0, etaMax, 1e-3 * etaMax, options_.lineSearchEvaluations - 1);
  return best;
}

// One iteration: linearise once, then damped directions (Levenberg-Marquardt on top of the paper's
// Gauss-Newton) until a line search improves the objective. The damping λ carries over between
// iterations: lowered after a full step, raised after a shortened one, raised tenfold after a failure.
std::optional<FitIteration> Fitter::iterate(const Stage& stage) {
  const auto started = std::chrono::steady_clock::now();
  Linearization lin = linearize(stage);
  std::optional<Trial> accepted;
  for (int attempt = 0; attempt < kDampingAttempts && !accepted; ++attempt) {
    accepted = lineSearch(stage, lin, attempt == 0 ? firstDirection(stage, lin) : boundedDirection(stage, lin));
    if (!accepted) damping_ *= 10;
  }
  if (!accepted) return std::nullopt;
  damping_ = accepted->eta >= 1.0 ? std::max(damping_ / 3, kMinDamping) : damping_ * 2;
  s_ = std::move(accepted->s);
  x_ = std::move(accepted->x);
  if (!attached_) realign(stage.markers);

  FitIteration record;
  record.stage = stage.name;
  record.step = accepted->eta;
  record.damping = damping_;
  record.smoothness = smoothness(s_);
  record.objective = objective(stage.markers, s_, x_);
  record.constraints = record.objective - record.smoothness;
  recordErrors(record);
  record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return record;
}

void Fitter::realign(Markers which) {
  const std::vector<PointConstraint> active = constraints(which, x_);
  MatrixX3d from(Eigen::Index(active.size()), 3), to(Eigen::Index(active.size()), 3);
  for (std::size_t k = 0; k < active.size(); ++k) {
    from.row(Eigen::Index(k)) = constrainedPoint(active[k], x_).transpose();
    to.row(Eigen::Index(k)) = active[k].target.transpose();
  }
  const SimilarityTransform rigid = fitSimilarity(from, to, Eigen::VectorXd(), false);
  x_ = PlasticFem::flatten(rigid.apply(PlasticFem::unflatten(x_)));
}

void Fitter::recordErrors(FitIteration& record) const {
  if (markers_.icp.rows() == 0) return;
  const Eigen::VectorXd d = surface_.distances(x_, markers_.icp);
  record.meanIcpError = d.mean();
  record.maxIcpError = d.maxCoeff();
}

FitResult Fitter::run(Progress* progress) {
  const Markers first = markers_.scanLandmarks.rows() ? Markers::Landmarks
                        : markers_.icp.rows()          ? Markers::Icp
                                                       : Markers::None;
  if (first == Markers::None && !attached_) throw BadInput("", "nothing to fit to: no landmarks, ICP markers or attachments");
  const Stage stages[] = {
      {"constant", first, true, options_.constantStrainIterations},
      {"attachments", Markers::None, false, attached_ && first == Markers::None ? options_.landmarkIterations : 0},
      {"landmarks", Markers::Landmarks, false, markers_.scanLandmarks.rows() ? options_.landmarkIterations : 0},
      {"icp", Markers::Icp, false, markers_.icp.rows() ? options_.icpIterations : 0},
  };
  std::vector<FitIteration> history;
  std::vector<FitStageEnd> ends;
  x_ = equilibrium(s_, x_, nullptr);
  if (!attached_ && first != Markers::None) realign(first);
  for (const Stage& stage : stages) {
    if (stage.maxIterations <= 0) continue;
    if (progress) progress->begin(std::string("fit: ") + stage.name);
    const double stageStart = objective(stage.markers, s_, x_);
    damping_ = kStartDamping;
    double previous = stageStart;
    FitStageEnd end{stage.name, 0, "iterations"};
    for (int k = 0; k < stage.maxIterations && end.reason == "iterations"; ++k) {
      std::optional<FitIteration> record = iterate(stage);
      if (!record) {
        end.reason = "no_descent";
        break;
      }
      record->iteration = k;
      history.push_back(*record);
      end.iterations = k + 1;
      if (progress) progress->update(double(k + 1) / stage.maxIterations);
      if (const char* reason = stopReason(stage, history, previous - record->objective, stageStart))
        end.reason = reason;
      previous = record->objective;
    }
    ends.push_back(end);
    if (progress) progress->end();
  }
  FitResult out = result(history);
  out.stageEnds = std::move(ends);
  return out;
}

// The rule that ends the stage after the last iteration of `history`, or nothing. decrease: what that
// iteration took off the objective, from stageStart at the stage's start.
const char* Fitter::stopReason(const Stage& stage, const std::vector<FitIteration>& history, double decrease,
                               double stageStart) const {
  const FitIteration& last = history.back();
  if (last.step < options_.minStep) return "step";
  if (decrease < options_.minDecrease * stageStart) return "objective";
  if (stage.markers != Markers::Icp || stage.constantStrain) return nullptr;
  if (last.maxIcpError < options_.maxIcpError) return "max_icp_error";
  const int window = options_.icpGainIterations;
  if (window <= 0 || last.iteration < window) return nullptr;
  const double before = history[history.size() - 1 - std::size_t(window)].meanIcpError;
  const double gain = before - last.meanIcpError;
  if (gain < options_.minIcpGain * before || gain < options_.minIcpGainMm) return "icp_gain";
  return nullptr;
}

FitResult Fitter::result(std::vector<FitIteration> history) const {
  FitResult result;
  result.attached = attached_;
  result.history = std::move(history);
  result.V = PlasticFem::unflatten(x_);
  result.s = scale_ * s_;
  result.icpErrors = surface_.distances(x_, markers_.icp);
  result.landmarkErrors.resize(Eigen::Index(landmarks_.size()));
  for (std::size_t k = 0; k < landmarks_.size(); ++k)
    result.landmarkErrors[Eigen::Index(k)] = (constrainedPoint(landmarks_[k], x_) - landmarks_[k].target).norm();
  return result;
}

FitResult Fitter::runElastic(Progress* progress) {
  // All markers become stiff springs on the template at its starting plastic state; ICP markers are
  // re-projected and the equilibrium re-solved until the closest points settle.
  std::vector<FitIteration> history;
  if (progress) progress->begin("fit: elastic");
  const int rounds = markers_.icp.rows() ? std::max(1, options_.icpIterations) : 1;
  for (int k = 0; k < rounds; ++k) {
    const auto started = std::chrono::steady_clock::now();
    std::vector<PointConstraint> markers = surface_.closestPoints(x_, markers_.icp, 1.0);
    markers.insert(markers.end(), landmarks_.begin(), landmarks_.end());
    PointSprings springs = asSprings(markers, options_.elasticMarkerStiffness * fem_.material().mu *
                                                  std::cbrt(fem_.restVolumes().sum()));
    const PointSprings held = asSprings(attachments_, springStiffness_);
    springs.points.insert(springs.points.end(), held.points.begin(), held.points.end());
    springs.targets.conservativeResize(springs.targets.rows() + held.targets.rows(), 3);
    springs.targets.bottomRows(held.targets.rows()) = held.targets;
    springs.stiffness.conservativeResize(springs.stiffness.size() + held.stiffness.size());
    springs.stiffness.tail(held.stiffness.size()) = held.stiffness;
    const Eigen::VectorXd before = x_;
    x_ = solveStaticEquilibrium(fem_, s_, springs, x_).x;
    FitIteration record;
    record.stage = "elastic";
    record.iteration = k;
    record.step = 1.0;
    recordErrors(record);
    record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    history.push_back(record);
    if (progress) progress->update(double(k + 1) / rounds);
    if ((x_ - before).cwiseAbs().maxCoeff() < 1e-3 * options_.maxIcpError) break;
  }
  if (progress) progress->end();
  return result(std::move(history));
}

}  // namespace

FitResult fitPlasticStrains(const TetMesh& templ, const MatrixX3d& x0, const Eigen::VectorXd& s0,
                            const FitMarkers& markers, const FitOptions& options, Progress* progress) {
  return Fitter(templ, x0, s0, markers, options).run(progress);
}

FitResult fitElastic(const TetMesh& templ, const MatrixX3d& x0, const Eigen::VectorXd& s0, const FitMarkers& markers,
                     const FitOptions& options, Progress* progress) {
  return Fitter(templ, x0, s0, markers, options).runElastic(progress);
}

}  // namespace vesalius::fit
