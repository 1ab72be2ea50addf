#pragma once
// What the fluid solver counts and sums from step to step: the source of SolverStats (its averages are
// these sums over the steps), and what a restart state carries so that a continued run's statistics
// go on as one uninterrupted run's would.
#include <cstdint>

namespace spume {

struct SolverCounters {
  uint64_t steps = 0;
  uint64_t density_iterations = 0, divergence_iterations = 0;  // summed over the steps
  uint64_t density_unconverged = 0, divergence_unconverged = 0;  // solves that hit the iteration limit
  uint64_t corrections = 0;        // fluid particles projected out of a solid after a step
  uint64_t dt_clamped_to_min = 0;  // steps where the CFL step was below min_dt
  uint64_t retries = 0;            // stretches taken again from the last good state with a smaller step
  double dt_sum = 0.0;             // s
  double density_error = 0.0, max_density_error = 0.0, divergence_error = 0.0;  // last, largest, last
  double min_dt_used = 0.0, max_dt_used = 0.0;  // s
  double step_cap = 0.0;  // s: the largest step the solver takes now; retries lower it for good
};

}  // namespace spume
