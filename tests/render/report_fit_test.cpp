// The convergence-order fit of `spume report` on closed-form series.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/app/report/convergence_fit.h"
#include "sim/core/error.h"

namespace spume::report {
namespace {

TEST(ReportFit, RecoversOrderAndCoefficientOfExactPowerLaws) {
  for (double order : {0.5, 1.0, 2.0, 4.0}) {
    std::vector<double> h, e;
    for (double step : {2.0, 1.0, 0.5, 0.25, 0.125}) h.push_back(step), e.push_back(3.0 * std::pow(step, order));
    const PowerFit f = fit_power_law(h, e);
    EXPECT_NEAR(f.order, order, 1e-12);
    EXPECT_NEAR(f.coefficient, 3.0, 1e-12);
    EXPECT_NEAR(f.r_squared, 1.0, 1e-12);
    EXPECT_EQ(f.points, 5);
  }
}

TEST(ReportFit, LeastSquaresOfANoisySeriesIsTheSlopeOfTheLogLogLine) {
  // e = h^2 * (1, 2, 1, 2). In units of ln 2, x = ln h = (0, -1, -2, -3) and ln m = (0, 1, 0, 1):
  // deviations from the means (1.5, 0.5, -0.5, -1.5) and (-0.5, 0.5, -0.5, 0.5) give cov = -1 and
  // var = 5, so the least-squares slope is 2 + cov / var = 1.8 exactly.
  const std::vector<double> h = {1.0, 0.5, 0.25, 0.125}, m = {1, 2, 1, 2};
  std::vector<double> e;
  for (size_t i = 0; i < h.size(); ++i) e.push_back(h[i] * h[i] * m[i]);
  const PowerFit f = fit_power_law(h, e);
  EXPECT_NEAR(f.order, 1.8, 1e-12);
  EXPECT_LT(f.r_squared, 1.0);
  EXPECT_GT(f.r_squared, 0.9);
}

TEST(ReportFit, ZeroAndNonFiniteErrorsAreLeftOut) {
  const std::vector<double> h = {1.0, 0.5, 0.25, 0.0}, e = {1.0, 0.25, 0.0, NAN};
  const PowerFit f = fit_power_law(h, e);
  EXPECT_EQ(f.points, 2);
  EXPECT_NEAR(f.order, 2.0, 1e-12);
}

TEST(ReportFit, TooFewPointsOrMismatchedSeriesAreErrors) {
  const std::vector<double> one = {1.0}, two = {1.0, 1.0};
  EXPECT_THROW(fit_power_law(one, one), Error);
  EXPECT_THROW(fit_power_law(two, std::vector<double>{1.0, 2.0}), Error);  // same step twice
  EXPECT_THROW(fit_power_law(two, one), Error);
}

}  // namespace
}  // namespace spume::report
