// Eq. 8's per-particle cap: a diffuse id numbers at most 4,095 samples per fluid
// particle and step; what the cap cuts is counted (EmissionResult::capped, FrameStats::capped,
// stats.csv) instead of vanishing silently.
#include <gtest/gtest.h>

#include <limits>

#include "sim/diffuse/emission.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

TEST(EmissionCap, RoundingCountsWhatTheCapCuts) {
  const RandomKey key{1, RandomPurpose::EmissionRounding, 0, 7, 0};
  const RoundedEmission at_cap = round_emission_counted(4095.0f, key);
  EXPECT_EQ(at_cap.count, 4095u);
  EXPECT_EQ(at_cap.capped, 0u);
  const RoundedEmission beyond = round_emission_counted(5000.0f, key);  // whole: no random part
  EXPECT_EQ(beyond.count, 4095u);
  EXPECT_EQ(beyond.capped, 905u);
  EXPECT_EQ(round_emission(5000.0f, key), 4095u);
  // Just below the cap nothing is cut, whichever way the fraction rounds.
  for (uint32_t id = 0; id < 100; ++id) {
    const RoundedEmission r = round_emission_counted(4094.5f, {1, RandomPurpose::EmissionRounding, 0, id, 0});
    EXPECT_TRUE(r.count == 4094u || r.count == 4095u) << r.count;
    EXPECT_EQ(r.capped, 0u);
  }
  // Absurd rates saturate rather than wrap.
  EXPECT_EQ(round_emission_counted(std::numeric_limits<float>::infinity(), key).count, 4095u);
  EXPECT_GT(round_emission_counted(std::numeric_limits<float>::infinity(), key).capped, uint64_t(1) << 63);
  EXPECT_GT(round_emission_counted(1e30f, key).capped, uint64_t(1) << 63);
}

TEST(EmissionCap, EmitDiffuseReportsTheCutAndEmitsTheRest) {
  // n_d = I_k k_ta I_ta dt with k_ta = 640000/s and dt = 1/64 s (both exact in float): 10000 for
  // particles 0 and 1 (I_ta = 1), 625 for particle 2 (I_ta = 1/16). Emitted 2 x 4095 + 625 = 8815;
  // cut 2 x (10000 - 4095) = 11810.
  const std::vector<Vec3f> x = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const FluidStepState state = testing::state_of(x, std::vector<Vec3f>(3, Vec3f(0, 1, 0)));
  FormationPotentials p;
  p.kinetic = {1, 1, 1};
  p.trapped_air = {1, 1, 0.0625f};
  p.wave_crest = {0, 0, 0};
  DiffuseParams params;
  params.k_ta = 640000.0f, params.k_wc = 0.0f;
  DiffuseFrame out;
  const EmissionResult r = emit_diffuse(state, p, params, 2, 1.0f / 64, 0.01f, out);
  EXPECT_EQ(r.requested, 8815u);
  EXPECT_EQ(r.emitted, 8815u);
  EXPECT_EQ(r.capped, 11810u);
  EXPECT_EQ(out.size(), 8815u);
  // Each capped parent numbers its 4,095 samples 0..4094.
  uint32_t max_sample = 0;
  for (uint64_t id : out.ids) max_sample = std::max(max_sample, diffuse_id_sample(id));
  EXPECT_EQ(max_sample, kMaxSamplesPerStep - 1);
}

}  // namespace
}  // namespace spume
