#include "render/app/report/convergence_fit.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "sim/core/error.h"

namespace spume::report {

PowerFit fit_power_law(std::span<const double> step, std::span<const double> error) {
  if (step.size() != error.size()) fail("convergence fit: ", step.size(), " steps for ", error.size(), " errors");
  std::vector<double> x, y;
  for (size_t i = 0; i < step.size(); ++i)
    if (step[i] > 0 && error[i] > 0 && std::isfinite(step[i]) && std::isfinite(error[i]))
      x.push_back(std::log(step[i])), y.push_back(std::log(error[i]));
  const double n = double(x.size());
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= n, my /= n;
  double sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < x.size(); ++i)
    sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my), syy += (y[i] - my) * (y[i] - my);
  if (x.size() < 2 || sxx <= 0)
    fail("convergence fit: need at least two points with positive error at different steps (got ", x.size(), ")");
  PowerFit f;
  f.order = sxy / sxx;
  f.coefficient = std::exp(my - f.order * mx);
  f.r_squared = syy > 0 ? sxy * sxy / (sxx * syy) : 1.0;
  f.points = int(x.size());
  return f;
}

std::string order_name(double order) {
  if (std::abs(order - 1.0) <= 0.2) return "first order";
  if (std::abs(order - 2.0) <= 0.2) return "second order";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "order %.3g", order);
  return buffer;
}

}  // namespace spume::report
