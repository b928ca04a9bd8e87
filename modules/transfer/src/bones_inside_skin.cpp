// The smallest similarity change that moves bones inside their skin (bones_inside_skin.h).
#include "vesalius/transfer/bones_inside_skin.h"

#include "vesalius/core/error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace vesalius::transfer {

namespace {

// x -> centre + shift + scale · turn · (x − centre).
struct Change {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), shift = Eigen::Vector3d::Zero();
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  double scale = 1.0;

  SimilarityTransform similarity() const {
    SimilarityTransform t;
    t.scale = scale;
    t.rotation = turn;
    t.translation = centre + shift - scale * turn * centre;
    return t;
  }
};

// The centre the change turns and scales about: the centroid, for a symmetric group projected onto the
// sagittal plane so that the change keeps the plane.
Eigen::Vector3d changeCentre(const MatrixX3d& V, const Plane* sagittal) {
  const Eigen::Vector3d centroid = V.colwise().mean().transpose();
  if (!sagittal) return centroid;
  const Eigen::Vector3d n = sagittal->normal.normalized();
  return centroid - n.dot(centroid - sagittal->point) * n;
}

// The parameters (δt, ω, δs) a step may use, as columns of a 7 by k basis: all seven for a free bone; for
// a symmetric group the two translations in the sagittal plane, the turn about its normal and the scale.
Eigen::MatrixXd stepBasis(const Plane* sagittal) {
  if (!sagittal) return Eigen::MatrixXd::Identity(7, 7);
  const Eigen::Vector3d n = sagittal->normal.normalized(), e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(7, 4);
  basis.block<3, 1>(0, 0) = e1;
  basis.block<3, 1>(0, 1) = e2;
  basis.block<3, 1>(3, 2) = n;
  basis(6, 3) = 1.0;
  return basis;
}

// The change's parameters (δt, ω, δs) from none: shift, rotation vector of the turn, scale − 1.
Eigen::Matrix<double, 7, 1> changeParameters(const Change& change) {
  const Eigen::AngleAxisd turn(change.turn);
  Eigen::Matrix<double, 7, 1> p;
  p << change.shift, turn.angle() * turn.axis(), change.scale - 1.0;
  return p;
}

// The anchors' terms weight · |change(a) − a|² added to the normal equations of a step about `centre`:
// a point moves by δt + ω × r + δs r, r its offset from the centre.
void addAnchors(const MatrixX3d& anchors, const Change& change, const Eigen::Vector3d& centre, double weight,
                Eigen::Matrix<double, 7, 7>& normal, Eigen::Matrix<double, 7, 1>& gradient) {
  const SimilarityTransform now = change.similarity();
  for (Eigen::Index a = 0; a < anchors.rows(); ++a) {
    const Eigen::Vector3d at = anchors.row(a).transpose(), moved = now.apply(at), r = moved - centre;
    Eigen::Matrix<double, 3, 7> j;
    j.leftCols<3>().setIdentity();
    for (int k = 0; k < 3; ++k) j.col(3 + k) = Eigen::Vector3d::Unit(k).cross(r);  // ∂(ω × r)/∂ω_k
    j.col(6) = r;
    normal += weight * j.transpose() * j;
    gradient += weight * j.transpose() * (moved - at);
  }
}

// One Gauss-Newton step of E (bones_inside_skin.h) over the vertices X (their distances d) and the anchors,
// about the change's current centre: (δt, ω, δs) in the basis's span. W counts the turn in mm at `radius`
// and a change of scale scaleCost times dearer. Levenberg-Marquardt damping of a tenth of the active
// vertices' weight in W keeps a step from overshooting where the linearised distances stop holding. Zero
// when every vertex is a margin inside.
Eigen::Matrix<double, 7, 1> hingeStep(const MatrixX3d& X, const SkinDistances& d, const MatrixX3d& anchors,
                                      const Change& change, const InsideSkinOptions& o, double radius,
                                      const Eigen::MatrixXd& basis) {
  const Eigen::Vector3d centre = change.centre + change.shift;
  Eigen::Matrix<double, 7, 7> normal = Eigen::Matrix<double, 7, 7>::Zero();
  Eigen::Matrix<double, 7, 1> gradient = Eigen::Matrix<double, 7, 1>::Zero();
  long active = 0;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    const double residual = d.distance[i] + o.marginMm;
    if (residual <= 0) continue;
    const Eigen::Vector3d n = d.outward.row(i).transpose(), r = X.row(i).transpose() - centre;
    Eigen::Matrix<double, 7, 1> j;
    j << n, r.cross(n), n.dot(r);
    normal += j * j.transpose();
    gradient += residual * j;
    ++active;
  }
  if (active == 0) return Eigen::Matrix<double, 7, 1>::Zero();
  addAnchors(anchors, change, centre, o.anchorWeight, normal, gradient);
  Eigen::Matrix<double, 7, 1> w;
  w << 1, 1, 1, radius * radius, radius * radius, radius * radius, o.scaleCost * radius * radius;
  const Eigen::Matrix<double, 7, 7> W = w.asDiagonal();
  const Eigen::Matrix<double, 7, 7> damped = normal + o.changeWeight * W + 0.1 * double(active) * W;
  const Eigen::MatrixXd reduced = basis.transpose() * damped * basis;
  return -basis * reduced.ldlt().solve(basis.transpose() * (gradient + o.changeWeight * W * changeParameters(change)));
}

// The step composed onto the change (about its current centre), then the caps.
void takeStep(Change& change, const Eigen::Matrix<double, 7, 1>& step, const InsideSkinOptions& o) {
  change.shift += step.head<3>();
  const Eigen::Vector3d omega = step.segment<3>(3);
  if (omega.norm() > 0) change.turn = Eigen::AngleAxisd(omega.norm(), omega.normalized()).toRotationMatrix() * change.turn;
  change.scale = std::max(o.minScale, change.scale * (1.0 + step[6]));
  if (change.shift.norm() > o.maxShiftMm) change.shift *= o.maxShiftMm / change.shift.norm();
  const Eigen::AngleAxisd turn(change.turn);
  const double maxTurn = o.maxTurnDegrees * M_PI / 180.0;
  if (turn.angle() > maxTurn) change.turn = Eigen::AngleAxisd(maxTurn, turn.axis()).toRotationMatrix();
}

long countOutside(const SkinDistances& d) { return long((d.distance.array() > 0).count()); }

}  // namespace

InsideSkinCorrection correctionIntoSkin(const MatrixX3d& V, const MatrixX3d& anchors, const SkinDistanceFunction& skin,
                                        const Plane* sagittal, const InsideSkinOptions& options) {
  if (V.rows() == 0) throw UsageError("correctionIntoSkin: no vertices");
  if (!(options.marginMm >= 0 && options.minScale > 0 && options.minScale <= 1 && options.maxShiftMm >= 0 &&
        options.maxTurnDegrees >= 0 && options.iterations >= 0 && options.anchorWeight >= 0 &&
        options.changeWeight > 0 && options.scaleCost > 0))
    throw UsageError("correctionIntoSkin: options out of range");
  Change change;
  change.centre = changeCentre(V, sagittal);
  const double radius = std::sqrt((V.rowwise() - change.centre.transpose()).rowwise().squaredNorm().mean());
  const Eigen::MatrixXd basis = stepBasis(sagittal);
  InsideSkinCorrection out;
  MatrixX3d X = V;
  SkinDistances d = skin(X);
  out.outsideBefore = countOutside(d);
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
    const Eigen::Matrix<double, 7, 1> step = hingeStep(X, d, anchors, change, options, radius, basis);
    if (step.head<3>().norm() + radius * step.tail<4>().norm() < 1e-3) break;
    takeStep(change, step, options);
    X = change.similarity().apply(V);
    d = skin(X);
  }
  out.change = change.similarity();
  out.outsideAfter = countOutside(d);
  return out;
}

}  // namespace vesalius::transfer
