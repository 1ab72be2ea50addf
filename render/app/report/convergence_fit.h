#pragma once
// Convergence order from an error series: least squares of log(error) on log(step), so that
// error ~ C step^order. Points with a non-positive or non-finite error or step are left out (an error
// of exactly 0 is the reference itself, not a measurement).
#include <span>
#include <string>

namespace spume::report {

struct PowerFit {
  double order = 0.0;        // slope of log(error) against log(step)
  double coefficient = 0.0;  // C
  double r_squared = 0.0;    // of the fit in log-log space (1 when every point lies on the line)
  int points = 0;            // used
};

// Throws Error when fewer than two usable points with distinct steps remain.
PowerFit fit_power_law(std::span<const double> step, std::span<const double> error);

// "first order" / "second order" when the fitted order is within 0.2 of 1 or 2, else "order 1.43".
std::string order_name(double order);

}  // namespace spume::report
