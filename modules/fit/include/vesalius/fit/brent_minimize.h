// Brent's derivative-free 1D minimization: golden-section search with parabolic interpolation (Brent
// 1973; Press et al., Numerical Recipes §10.3). The fitter's line search on the step η ∈ [0, ηmax]
// uses it (Wang et al. 2021, §3.4), because each evaluation is an equilibrium solve and there is no gradient.
#pragma once

#include <functional>

namespace vesalius::fit {

struct BrentResult {
  double x;         // the best point evaluated
  double fx;        // f(x)
  int evaluations;  // calls of f, at most maxEvaluations
};

// Minimizes f on [a, b] (a < b, both finite). Stops when the bracket around x has shrunk so that x is
// within `tolerance` + 3e-8 |x| of a local minimizer (tolerance: absolute, on x, > 0).
// Contract:
//   - f is evaluated only at interior points, never at a or b; the first point is the golden-section
//     point a + 0.382 (b − a). A caller that needs "never worse than f(a)" (the line search, whose
//     f(0) is the current energy) compares the result against its own f(a).
//   - The returned x is the point with the lowest value among all evaluations; NaN values count as +∞.
//   - After maxEvaluations (>= 1) calls of f the best point so far is returned; this is not an error.
//   - Exceptions thrown by f propagate.
// Throws BadInput on an empty or non-finite interval, tolerance <= 0 or maxEvaluations < 1.
BrentResult minimizeBrent(const std::function<double(double)>& f, double a, double b, double tolerance,
                          int maxEvaluations);

}  // namespace vesalius::fit
