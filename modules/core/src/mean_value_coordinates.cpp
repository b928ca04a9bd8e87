#include "vesalius/core/mean_value_coordinates.h"

#include "vesalius/core/error.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace vesalius {

namespace {

constexpr double kEpsilon = 1e-9;
constexpr double kPi = 3.14159265358979323846;

// One point's interpolation (the paper's Figure 4, with its notation: u unit vectors to the vertices, d
// their distances, theta the arcs of the spherical triangle, c and s its angles' cosines and sines).
Eigen::RowVectorXd interpolateAt(const TriMesh& cage, const Eigen::MatrixXd& values, const Eigen::Vector3d& x) {
  const Eigen::Index n = cage.V.rows();
  Eigen::VectorXd d(n);
  MatrixX3d u(n, 3);
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::Vector3d to = cage.V.row(j).transpose() - x;
    d[j] = to.norm();
    if (d[j] < kEpsilon) return values.row(j);
    u.row(j) = to.transpose() / d[j];
  }
  Eigen::RowVectorXd total = Eigen::RowVectorXd::Zero(values.cols());
  double totalWeight = 0;
  for (Eigen::Index f = 0; f < cage.F.rows(); ++f) {
    const int p[3] = {cage.F(f, 0), cage.F(f, 1), cage.F(f, 2)};
    double theta[3], l[3];
    for (int i = 0; i < 3; ++i) {
      l[i] = (u.row(p[(i + 1) % 3]) - u.row(p[(i + 2) % 3])).norm();
      theta[i] = 2 * std::asin(std::min(1.0, l[i] / 2));
    }
    const double h = (theta[0] + theta[1] + theta[2]) / 2;
    if (kPi - h < kEpsilon) {  // x lies on the triangle: its barycentric coordinates
      Eigen::RowVectorXd onTriangle = Eigen::RowVectorXd::Zero(values.cols());
      double sum = 0;
      for (int i = 0; i < 3; ++i) {
        const double w = std::sin(theta[i]) * d[p[(i + 2) % 3]] * d[p[(i + 1) % 3]];
        onTriangle += w * values.row(p[i]);
        sum += w;
      }
      return onTriangle / sum;
    }
    Eigen::Matrix3d U;
    U << u.row(p[0]), u.row(p[1]), u.row(p[2]);
    const double sign = U.determinant() < 0 ? -1.0 : 1.0;
    double c[3], s[3];
    bool coplanar = false;
    for (int i = 0; i < 3; ++i) {
      c[i] = 2 * std::sin(h) * std::sin(h - theta[i]) / (std::sin(theta[(i + 1) % 3]) * std::sin(theta[(i + 2) % 3])) - 1;
      s[i] = sign * std::sqrt(std::max(0.0, 1 - c[i] * c[i]));
      if (std::abs(s[i]) <= kEpsilon) coplanar = true;
    }
    if (coplanar) continue;  // x is in the triangle's plane but outside it: the triangle adds nothing
    for (int i = 0; i < 3; ++i) {
      const int next = (i + 1) % 3, previous = (i + 2) % 3;
      const double w = (theta[i] - c[next] * theta[previous] - c[previous] * theta[next]) /
                       (d[p[i]] * std::sin(theta[next]) * s[previous]);
      total += w * values.row(p[i]);
      totalWeight += w;
    }
  }
  return total / totalWeight;
}

}  // namespace

Eigen::MatrixXd meanValueInterpolate(const TriMesh& cage, const Eigen::MatrixXd& values, const MatrixX3d& points) {
  if (cage.F.rows() == 0) throw BadInput("", "mean value coordinates: the cage has no triangles");
  if (values.rows() != cage.V.rows())
    throw BadInput("", "mean value coordinates: " + std::to_string(values.rows()) + " values for " +
                           std::to_string(cage.V.rows()) + " cage vertices");
  Eigen::MatrixXd out(points.rows(), values.cols());
  tbb::parallel_for(Eigen::Index(0), points.rows(),
                    [&](Eigen::Index i) { out.row(i) = interpolateAt(cage, values, points.row(i).transpose()); });
  return out;
}

}  // namespace vesalius
