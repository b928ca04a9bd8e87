#include "vesalius/fit/brent_minimize.h"

#include "vesalius/core/error.h"

#include <cmath>
#include <limits>

namespace vesalius::fit {

BrentResult minimizeBrent(const std::function<double(double)>& f, double a, double b, double tolerance,
                          int maxEvaluations) {
  if (!(std::isfinite(a) && std::isfinite(b) && a < b)) throw BadInput("", "Brent minimization: empty interval");
  if (!(tolerance > 0.0) || maxEvaluations < 1)
    throw BadInput("", "Brent minimization: tolerance and the evaluation budget must be positive");
  const double golden = 0.5 * (3.0 - std::sqrt(5.0));
  const double relative = std::sqrt(std::numeric_limits<double>::epsilon());
  int evaluations = 0;
  const auto evaluate = [&](double u) {
    ++evaluations;
    const double value = f(u);
    return std::isnan(value) ? std::numeric_limits<double>::infinity() : value;
  };
  // x: best point so far; w: second best; v: previous w. [a, b] brackets the minimum being approached.
  double x = a + golden * (b - a), w = x, v = x;
  double fx = evaluate(x), fw = fx, fv = fx;
  double d = 0.0, e = 0.0;  // the last step and the one before it
  while (evaluations < maxEvaluations) {
    const double middle = 0.5 * (a + b), tol1 = relative * std::abs(x) + tolerance / 3.0, tol2 = 2.0 * tol1;
    if (std::abs(x - middle) <= tol2 - 0.5 * (b - a)) break;
    bool parabolic = false;
    if (std::abs(e) > tol1) {
      // Parabola through (v, fv), (w, fw), (x, fx); accept its vertex x + p/q only if it lies inside the
      // bracket and the step is less than half the step before last (else the search could cycle).
      const double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0) p = -p;
      q = std::abs(q);
      const double stepBeforeLast = e;
      e = d;
      if (std::abs(p) < std::abs(0.5 * q * stepBeforeLast) && p > q * (a - x) && p < q * (b - x)) {
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = x < middle ? tol1 : -tol1;
        parabolic = true;
      }
    }
    if (!parabolic) {
      e = x < middle ? b - x : a - x;  // golden section into the larger part
      d = golden * e;
    }
    const double u = x + (std::abs(d) >= tol1 ? d : std::copysign(tol1, d));
    const double fu = evaluate(u);
    if (fu <= fx) {
      (u < x ? b : a) = x;
      v = w, fv = fw;
      w = x, fw = fx;
      x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw;
        w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return {x, fx, evaluations};
}

}  // namespace vesalius::fit
