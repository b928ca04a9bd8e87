#include "vesalius/fit/brent_minimize.h"

#include "vesalius/core/error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace vesalius::fit {
namespace {

// Runs Brent on f, recording every point it evaluates.
struct Recorded {
  BrentResult result;
  std::vector<double> xs, fs;
};

template <class F>
Recorded run(F f, double a, double b, double tolerance, int maxEvaluations) {
  Recorded r;
  r.result = minimizeBrent(
      [&](double x) {
        r.xs.push_back(x);
        r.fs.push_back(f(x));
        return r.fs.back();
      },
      a, b, tolerance, maxEvaluations);
  EXPECT_EQ(r.result.evaluations, int(r.xs.size()));
  EXPECT_LE(r.result.evaluations, maxEvaluations);
  for (double x : r.xs) {
    EXPECT_GT(x, a);
    EXPECT_LT(x, b);
  }
  return r;
}

TEST(MinimizeBrent, QuadraticNeedsFewEvaluations) {
  const auto r = run([](double x) { return (x - 0.3) * (x - 0.3) + 1.0; }, 0.0, 1.0, 1e-8, 100);
  EXPECT_NEAR(r.result.x, 0.3, 1e-8);
  EXPECT_NEAR(r.result.fx, 1.0, 1e-15);
  EXPECT_LE(r.result.evaluations, 12);
  RecordProperty("evaluations", r.result.evaluations);
}

TEST(MinimizeBrent, NonSmoothAbsoluteValue) {
  const double c = 0.7123;
  const auto r = run([c](double x) { return std::abs(x - c); }, -1.0, 2.0, 1e-6, 200);
  EXPECT_NEAR(r.result.x, c, 2e-6);
  EXPECT_LE(r.result.evaluations, 60);
  RecordProperty("evaluations", r.result.evaluations);
}

TEST(MinimizeBrent, MinimumAtABoundary) {
  const auto left = run([](double x) { return x; }, 0.0, 1.0, 1e-5, 200);
  EXPECT_LT(left.result.x, 2e-5);
  const auto right = run([](double x) { return -std::exp(x); }, 0.0, 2.0, 1e-5, 200);
  EXPECT_GT(right.result.x, 2.0 - 2e-5);
  EXPECT_LE(std::max(left.result.evaluations, right.result.evaluations), 60);
}

TEST(MinimizeBrent, ReturnsTheBestPointWithinTheBudget) {
  const auto f = [](double x) { return std::cos(3.0 * x) + 0.1 * x; };
  for (int budget : {1, 2, 5, 9}) {
    const auto r = run(f, 0.0, 4.0, 1e-10, budget);
    EXPECT_EQ(r.result.evaluations, budget);
    EXPECT_EQ(r.result.fx, *std::min_element(r.fs.begin(), r.fs.end()));
    EXPECT_EQ(r.result.fx, f(r.result.x));
  }
}

TEST(MinimizeBrent, NanCountsAsInfinity) {
  const auto r = run(
      [](double x) { return x > 0.6 ? std::numeric_limits<double>::quiet_NaN() : (x - 0.4) * (x - 0.4); }, 0.0,
      1.0, 1e-7, 100);
  EXPECT_NEAR(r.result.x, 0.4, 1e-6);
}

TEST(MinimizeBrent, PropagatesExceptionsAndRejectsBadArguments) {
  const auto thrower = [](double) -> double { throw std::runtime_error("equilibrium solve failed"); };
  EXPECT_THROW(minimizeBrent(thrower, 0.0, 1.0, 1e-6, 10), std::runtime_error);
  const auto f = [](double x) { return x * x; };
  EXPECT_THROW(minimizeBrent(f, 1.0, 1.0, 1e-6, 10), BadInput);
  EXPECT_THROW(minimizeBrent(f, 0.0, std::numeric_limits<double>::infinity(), 1e-6, 10), BadInput);
  EXPECT_THROW(minimizeBrent(f, 0.0, 1.0, 0.0, 10), BadInput);
  EXPECT_THROW(minimizeBrent(f, 0.0, 1.0, 1e-6, 0), BadInput);
}

}  // namespace
}  // namespace vesalius::fit
