// Unreasonable formation settings: equal or crossed clamp thresholds are refused; emission rates so
// large that the budget binds are capped exactly at the budget, and the thinning is unbiased in
// space (a fixed-seed chi-square test against uniform random thinning).
#include <gtest/gtest.h>

#include <algorithm>
#include <unordered_map>

#include "tests/stability/stability_support.h"

namespace spume {
namespace {

using stability::error_of;

TEST(StabilityThresholds, EqualOrCrossedClampsAreRefusedNamingTheKey) {
  for (const char* key : {"tau_ta", "tau_wc", "tau_k"})
    for (const std::pair<double, double>& clamp : {std::pair{3.0, 3.0}, std::pair{5.0, 2.0}}) {
      const double lo = clamp.first, hi = clamp.second;  // a lambda captures these under clang 14
      const std::string message = error_of([&] { stability::setup_with(0.02f, {{key, {lo, hi}}}); });
      EXPECT_NE(message.find(str("/", key)), std::string::npos) << message;
      EXPECT_NE(message.find(str("min ", lo, " must be below max ", hi)), std::string::npos) << message;
    }
  // Just apart is fine: the clamp divides by max - min, which is then small but not zero.
  EXPECT_NO_THROW(stability::setup_with(0.02f, {{"tau_ta", {3.0, 3.0001}}}));
}

// The particles one emission step produces from frame `k` of a collision, on a fresh simulator.
DiffuseFrame emitted_at(const std::vector<FluidFrame>& fluid, int k, const Json& diffuse, FrameStats* stats) {
  DiffuseSimulator sim(stability::setup_with(0.02f, diffuse));
  sim.process_frame(fluid[k], &fluid[k + 1], [](const DiffuseFrame&, const FrameStats&) {});
  // The work of the step is reported with the next frame.
  FrameStats s = sim.process_frame(fluid[k + 1], nullptr, [](const DiffuseFrame&, const FrameStats&) {});
  if (stats) *stats = s;
  return sim.particles();
}

// Chi-square of kept-per-bin counts against uniform random thinning of `all` down to `kept`:
// bin b holding C_b of the R candidates keeps a hypergeometric count, mean C_b M / R and variance
// C_b (M/R) (1 - M/R) (R - C_b) / (R - 1).
template <typename BinOf>
double thinning_chi_square(const DiffuseFrame& all, const DiffuseFrame& kept, int bins, BinOf bin_of) {
  std::vector<double> candidates(bins, 0.0), survivors(bins, 0.0);
  for (size_t i = 0; i < all.size(); ++i) candidates[bin_of(all, i)] += 1.0;
  for (size_t i = 0; i < kept.size(); ++i) survivors[bin_of(kept, i)] += 1.0;
  const double R = double(all.size()), M = double(kept.size()), f = M / R;
  double chi2 = 0.0;
  for (int b = 0; b < bins; ++b) {
    if (candidates[b] < 2) continue;
    const double mean = candidates[b] * f, var = candidates[b] * f * (1 - f) * (R - candidates[b]) / (R - 1);
    chi2 += (survivors[b] - mean) * (survivors[b] - mean) / var;
  }
  return chi2;
}

TEST(StabilityBudget, HugeRatesAreCappedAtTheBudgetAndThinnedWithoutSpatialBias) {
  const auto fluid = stability::colliding_blocks(0.02f, 0.3f, 2.0f, 1.0 / 50, 5);
  const Json rates = {{"k_ta", 1e6}, {"k_wc", 1e6}};
  FrameStats free_stats, capped_stats;
  const DiffuseFrame all = emitted_at(fluid, 2, rates, &free_stats);
  ASSERT_GT(all.size(), 20000u);
  EXPECT_EQ(free_stats.dropped, 0u);
  const uint64_t budget = all.size() / 4;
  Json capped_keys = rates;
  capped_keys["max_particles"] = budget;
  const DiffuseFrame kept = emitted_at(fluid, 2, capped_keys, &capped_stats);
  // Capped exactly, and the refused ones counted.
  EXPECT_EQ(kept.size(), budget);
  EXPECT_EQ(capped_stats.generated, budget);
  EXPECT_EQ(capped_stats.dropped, all.size() - budget);
  // The budget thins; it does not move anything: every kept particle is one of the candidates.
  std::unordered_map<uint64_t, Vec3f> where;
  for (size_t i = 0; i < all.size(); ++i) where[all.ids[i]] = all.positions[i];
  for (size_t i = 0; i < kept.size(); ++i) {
    const auto it = where.find(kept.ids[i]);
    ASSERT_NE(it, where.end()) << "kept particle " << i << " was never a candidate";
    ASSERT_EQ(it->second, kept.positions[i]);
  }
  // Unbiased: per axis, 8 slabs of the candidates' box; and by parent id (emission order), 8 bins.
  // 99.9% quantile of chi-square with 8 degrees of freedom: 26.12.
  Aabb box;
  for (const Vec3f& p : all.positions) box.extend(p);
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = box.min[axis], width = (box.max[axis] - box.min[axis]) / 8.0f;
    const double chi2 = thinning_chi_square(all, kept, 8, [&](const DiffuseFrame& f, size_t i) {
      return std::clamp(int((f.positions[i][axis] - lo) / width), 0, 7);
    });
    EXPECT_LT(chi2, 26.12) << "axis " << axis;
  }
  const uint32_t fluid_count = uint32_t(fluid[2].size());
  const double chi2_id = thinning_chi_square(all, kept, 8, [&](const DiffuseFrame& f, size_t i) {
    return int(uint64_t(diffuse_id_parent(f.ids[i])) * 8 / fluid_count);
  });
  EXPECT_LT(chi2_id, 26.12);
}

TEST(StabilityBudget, TheBudgetHoldsAtEveryFrameOfARun) {
  const auto fluid = stability::colliding_blocks(0.02f, 0.3f, 2.0f, 1.0 / 50, 10);
  DiffuseSetup setup = stability::setup_with(0.02f, {{"k_ta", 1e6}, {"k_wc", 1e6}, {"max_particles", 5000}});
  setup.domain.min = Vec3f(-2, -1, -1), setup.domain.max = Vec3f(2, 3, 2);
  DiffuseSimulator sim(setup);
  const auto run = stability::run_checked(sim, fluid);
  EXPECT_LE(run.max_particles, 5000u);
  EXPECT_LE(sim.particles().size(), 5000u);
  EXPECT_GT(run.dropped, 0u);
}

}  // namespace
}  // namespace spume
