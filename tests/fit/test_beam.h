// The beam of Wang et al.'s Figs. 4 and 22, shared by the fit's tests: a 60 mm box of tets, its ends' bottom
// edges attached to where a bend of radius 60 mm takes them, ICP markers on the rest of its surface
// where the bend and a doubling of its z thickness take them.
#pragma once

#include "vesalius/fit/plastic_fit.h"

#include "test_tets.h"

#include <cmath>
#include <vector>

namespace vesalius::fit::test_beam {

inline void append(MatrixX3d& M, const Eigen::Vector3d& p) {
  M.conservativeResize(M.rows() + 1, 3);
  M.row(M.rows() - 1) = p.transpose();
}

// The beam of Figs. 4 and 22: bent over a radius of 60 mm, doubled in its z thickness.
inline Eigen::Vector3d bentAndStretched(const Eigen::Vector3d& X) {
  const double R = 60, theta = X.x() / R, r = R - X.y();
  return Eigen::Vector3d(r * std::sin(theta), R - r * std::cos(theta), 2 * X.z());
}

inline TetMesh beamTets() {
  TetMesh beam = test::boxTets(12, 3, 4, 5.0);
  beam.V.col(1).array() -= 7.5;
  beam.V.col(2).array() -= 10.0;
  return beam;
}

// Its ends' bottom edges attached to where the bend takes them, ICP markers on the rest of its surface.
inline FitMarkers beamMarkers(const TetMesh& beam) {
  FitMarkers m;
  const MatrixX3i faces = tetBoundary(beam.T);
  std::vector<bool> onSurface(std::size_t(beam.V.rows()), false);
  for (Eigen::Index f = 0; f < faces.rows(); ++f)
    for (int j = 0; j < 3; ++j) onSurface[std::size_t(faces(f, j))] = true;
  for (Eigen::Index v = 0; v < beam.V.rows(); ++v) {
    const Eigen::Vector3d X = beam.V.row(v).transpose();
    if ((X.x() == 0.0 || X.x() == 60.0) && X.z() == 0.0) {
      append(m.attachmentMaterial, X);
      append(m.attachmentTargets, bentAndStretched(X));
    } else if (onSurface[std::size_t(v)] && X.x() > 0.0 && X.x() < 60.0) {
      append(m.icp, bentAndStretched(X));
    }
  }
  return m;
}

}  // namespace vesalius::fit::test_beam
