// Body frame and head extraction (body_frame.h).
#include "vesalius/transfer/body_frame.h"

#include "vesalius/core/error.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace vesalius::transfer {

namespace {

// One transverse cut: the crossing points of the mesh edges with the plane n·x = level.
struct Slice {
  double level = 0;
  std::vector<Eigen::Vector3d> points;  // two per crossed triangle (segment ends)
  double perimeter = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of the polygon curve (length-weighted)
  Eigen::Vector3d majorAxis = Eigen::Vector3d::Zero();
  double diameter = 0;    // extent along the major axis
  double elongation = 1;  // sqrt(λ1/λ2) of the points' in-plane covariance
};

Eigen::Vector3d edgeCrossing(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double da, double db) {
  return a + (da / (da - db)) * (b - a);
}

// The principal axes of points in the plane with normal n: the unit major axis and the eigenvalues.
Eigen::Vector3d planarMajorAxis(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& n,
                                Eigen::Vector2d& eigenvalues) {
  const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& p : points) mean += Eigen::Vector2d(u.dot(p), w.dot(p));
  mean /= double(points.size());
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector2d q = Eigen::Vector2d(u.dot(p), w.dot(p)) - mean;
    covariance += q * q.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance / double(points.size()));
  eigenvalues = eigen.eigenvalues();  // increasing
  const Eigen::Vector2d major = eigen.eigenvectors().col(1);
  return major.x() * u + major.y() * w;
}

Slice cut(const MatrixX3d& V, const MatrixX3i& F, const Eigen::Vector3d& n, double level) {
  Slice s;
  s.level = level;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    Eigen::Vector3d corner[3];
    double d[3];
    for (int k = 0; k < 3; ++k) {
      corner[k] = V.row(F(f, k)).transpose();
      d[k] = n.dot(corner[k]) - level;
    }
    Eigen::Vector3d ends[2];
    int count = 0;
    for (int k = 0; k < 3; ++k) {  // a corner exactly on the plane counts as above it
      const int l = (k + 1) % 3;
      if ((d[k] >= 0) != (d[l] >= 0) && count < 2) ends[count++] = edgeCrossing(corner[k], corner[l], d[k], d[l]);
    }
    if (count != 2) continue;
    const double length = (ends[1] - ends[0]).norm();
    s.perimeter += length;
    s.centroid += length * 0.5 * (ends[0] + ends[1]);
    s.points.push_back(ends[0]);
    s.points.push_back(ends[1]);
  }
  if (s.points.size() < 6 || !(s.perimeter > 0)) return s;
  s.centroid /= s.perimeter;
  Eigen::Vector2d lambda;
  s.majorAxis = planarMajorAxis(s.points, n, lambda);
  s.elongation = std::sqrt(lambda[1] / std::max(lambda[0], 1e-300));
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector3d& p : s.points) {
    lo = std::min(lo, s.majorAxis.dot(p));
    hi = std::max(hi, s.majorAxis.dot(p));
  }
  s.diameter = hi - lo;
  return s;
}

void checkOptions(const BodyFrameOptions& o) {
  if (!(o.sliceSpacing > 0)) throw UsageError("body frame: sliceSpacing must be positive");
  if (!(o.shrinkRatio > 0 && o.shrinkRatio < 1)) throw UsageError("body frame: shrinkRatio must be in (0, 1)");
  if (!(o.axisSwitchDegrees > 0 && o.axisSwitchDegrees <= 90))
    throw UsageError("body frame: axisSwitchDegrees must be in (0, 90]");
  if (!(o.minElongation >= 1)) throw UsageError("body frame: minElongation must be at least 1");
  if (!(o.jointDepthFraction >= 0 && o.jointDepthFraction <= 1))
    throw UsageError("body frame: jointDepthFraction must be in [0, 1]");
}

// Cuts from the top down until one of the two criteria fires; returns the head's cuts and sets the stop.
std::vector<Slice> headSlices(const MatrixX3d& V, const MatrixX3i& F, const Eigen::Vector3d& n,
                              const BodyFrameOptions& o, BodyFrame& frame) {
  const Eigen::VectorXd height = V * n;
  const double top = height.maxCoeff(), bottom = height.minCoeff();
  const double cosSwitch = std::cos(o.axisSwitchDegrees * M_PI / 180.0);
  std::vector<Slice> head;
  int widest = -1;
  for (double level = top - 0.5 * o.sliceSpacing; level > bottom; level -= o.sliceSpacing) {
    Slice s = cut(V, F, n, level);
    if (s.diameter == 0) {
      if (head.empty()) continue;  // the crown's first cut may miss every triangle
      throw BadInput("", "body frame: a transverse cut of the head is empty (is the skin open there?)");
    }
    if (widest >= 0) {
      const Slice& w = head[std::size_t(widest)];
      const bool shrink = s.diameter < o.shrinkRatio * w.diameter;
      const bool turned = s.elongation >= o.minElongation && std::abs(s.majorAxis.dot(w.majorAxis)) <= cosSwitch;
      if (shrink || turned) {
        frame.stopLevel = level;
        frame.stoppedByShrink = shrink;
        return head;
      }
    }
    head.push_back(std::move(s));
    if (widest < 0 || head.back().diameter > head[std::size_t(widest)].diameter) widest = int(head.size()) - 1;
  }
  throw BadInput("", "body frame: no transverse cut ends the head (neither criterion fired)");
}

// The head-spine joint: the centroid on the cut reaching furthest forward, at `fraction` of that cut's
// back-to-front extent.
Eigen::Vector3d headSpineJoint(const std::vector<Slice>& head, const BodyFrame& f, double fraction) {
  const Eigen::Vector3d forward = -f.frontalNormal;
  double furthest = -std::numeric_limits<double>::infinity();
  const Slice* nose = nullptr;
  for (const Slice& s : head)
    for (const Eigen::Vector3d& p : s.points)
      if (forward.dot(p) > furthest) {
        furthest = forward.dot(p);
        nose = &s;
      }
  double back = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : nose->points) back = std::min(back, forward.dot(p));
  Eigen::Vector3d joint = f.headCentroid + (nose->level - f.transverseNormal.dot(f.headCentroid)) * f.transverseNormal;
  joint += (back + fraction * (furthest - back) - forward.dot(joint)) * forward;
  return joint;
}

}  // namespace

Eigen::Matrix3d BodyFrame::axes() const {
  Eigen::Matrix3d a;
  a << sagittalNormal, frontalNormal, transverseNormal;
  return a;
}

BodyFrame computeBodyFrame(const MatrixX3d& V, const MatrixX3i& F, const LegJoints& legs,
                           const BodyFrameOptions& options) {
  checkOptions(options);
  if (V.rows() == 0 || F.rows() == 0) throw BadInput("", "body frame: the skin is empty");
  BodyFrame frame;
  const Eigen::Vector3d up = (legs.leftHip - legs.leftAnkle) + (legs.rightHip - legs.rightAnkle);
  if (!(up.norm() > 0) || !up.allFinite()) throw BadInput("", "body frame: the legs give no up direction");
  frame.transverseNormal = up.normalized();
  const std::vector<Slice> head = headSlices(V, F, frame.transverseNormal, options, frame);
  frame.headSlices = int(head.size());

  std::vector<Eigen::Vector3d> all;
  double perimeter = 0;
  frame.headCentroid.setZero();
  for (const Slice& s : head) {
    all.insert(all.end(), s.points.begin(), s.points.end());
    frame.headCentroid += s.perimeter * s.centroid;
    perimeter += s.perimeter;
  }
  frame.headCentroid /= perimeter;
  // Projecting into one transverse plane is dropping the normal component, which the in-plane PCA does.
  Eigen::Vector2d lambda;
  const Eigen::Vector3d forwardAxis = planarMajorAxis(all, frame.transverseNormal, lambda);
  Eigen::Vector3d left = frame.transverseNormal.cross(forwardAxis).normalized();
  const Eigen::Vector3d legsLeft = (legs.leftHip - legs.rightHip) + (legs.leftAnkle - legs.rightAnkle);
  if (left.dot(legsLeft) < 0) left = -left;
  frame.sagittalNormal = left;
  frame.frontalNormal = frame.transverseNormal.cross(left);
  frame.sagittalPoint = frame.headCentroid;
  frame.headSpineJoint = headSpineJoint(head, frame, options.jointDepthFraction);
  return frame;
}

}  // namespace vesalius::transfer
