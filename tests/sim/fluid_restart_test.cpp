// The solver's restart state (fluid/restart_state.h): a solver restored from a saved state steps to
// the same bytes as the solver that saved it, for any thread count, with a moving solid and with
// warm start; the file round-trips every field exactly and refuses corrupt copies; states that do
// not fit the solver, and solvers with dynamic bodies, are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/fluid/solver.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

Solid tank() {
  Solid t;
  t.kind = Solid::Kind::Tank;
  t.min = Vec3f(0, 0, 0);
  t.max = Vec3f(0.4f, 0.4f, 0.16f);
  return t;
}

// A sine piston against the column's back, already moving at t = 0, so the fluid touches a moving
// boundary in every restored step.
Solid piston() {
  Solid p;
  p.kind = Solid::Kind::Box;
  p.min = Vec3f(0.0f, 0.0f, 0.0f);
  p.max = Vec3f(0.04f, 0.4f, 0.16f);
  p.motion.kind = Motion::Kind::Sine;
  p.motion.axis = Vec3f::UnitX();
  p.motion.amplitude = 0.03f;
  p.motion.frequency = 2.0f;
  p.motion.phase = 1.0f;
  return p;
}

struct Scene {
  FluidSolverParams params;
  std::vector<FluidBlock> blocks;
  SolidSet solids;
  FluidSolver make() const { return FluidSolver(params, blocks, solids); }
};

// A 0.16 m column collapsing (r = 0.01 m: 8 x 20 x 8 = 1280 particles), in front of the piston if any.
Scene column(bool with_piston, bool warm_start) {
  Scene s;
  s.params.particle_radius = 0.01f;
  s.params.warm_start = warm_start;
  const float back = with_piston ? 0.06f : 0.0f;
  s.blocks = {FluidBlock{Vec3f(back, 0, 0), Vec3f(back + 0.16f, 0.4f, 0.16f)}};
  std::vector<Solid> solids = {tank()};
  if (with_piston) solids.push_back(piston());
  s.solids = SolidSet(solids);
  return s;
}

// Runs `setup` to t1, saves (through the file), restores into a fresh solver with `threads_after`
// threads and runs both to t2; every frame in between must be the same bytes.
void expect_continuation_identical(const Scene& setup, double t1, double t2, int threads_after) {
  set_thread_count(1);
  FluidSolver straight = setup.make();
  straight.advance_to(t1);
  const testing::TempDir temp;
  const fs::path file = temp / "state.spr";
  write_restart_state(file, straight.restart_state(7));
  set_thread_count(threads_after);
  FluidSolver resumed = setup.make();
  resumed.restore(read_restart_state(file));
  EXPECT_EQ(resumed.time(), t1);
  for (int k = 1; k <= 4; ++k) {
    const double t = t1 + (t2 - t1) * k / 4.0;
    set_thread_count(1);
    straight.advance_to(t);
    set_thread_count(threads_after);
    resumed.advance_to(t);
    const FluidFrame a = straight.frame(k), b = resumed.frame(k);
    EXPECT_TRUE(same_bytes(a.positions, b.positions)) << "t = " << t;
    EXPECT_TRUE(same_bytes(a.velocities, b.velocities)) << "t = " << t;
    const SolverStats sa = straight.stats(), sb = resumed.stats();
    EXPECT_EQ(sa.steps, sb.steps);
    EXPECT_EQ(sa.average_dt, sb.average_dt);
    EXPECT_EQ(sa.average_density_iterations, sb.average_density_iterations);
    EXPECT_EQ(sa.average_divergence_iterations, sb.average_divergence_iterations);
    EXPECT_EQ(sa.max_density_error, sb.max_density_error);
    EXPECT_EQ(sa.corrections, sb.corrections);
  }
  set_thread_count(0);
  // The flow did move between the save and the end (a comparison of resting fluid proves little).
  const FluidFrame end = straight.frame(0);
  double speed = 0.0;
  for (const Vec3f& v : end.velocities) speed = std::max(speed, double(v.norm()));
  EXPECT_GT(speed, 0.3);
}

TEST(FluidRestart, RestoredSolverContinuesByteIdentically) {
  expect_continuation_identical(column(false, false), 0.2, 0.3, 1);  // the CFL step binds: dt_prev != max_dt
}

TEST(FluidRestart, RestoredSolverWithAMovingSolidAndTwoThreadsContinuesByteIdentically) {
  expect_continuation_identical(column(true, false), 0.12, 0.2, 2);
}

TEST(FluidRestart, WarmStartPressuresAreCarried) {
  expect_continuation_identical(column(false, true), 0.1, 0.16, 2);
}

TEST(FluidRestart, FileRoundTripsEveryField) {
  FluidRestartState s;
  s.frame = 42;
  s.time = 0.123456789012345;
  s.dt_prev = 1.0 / 3.0 * 1e-3;
  s.particle_radius = 0.0125f;
  s.digest = "0123456789abcdef";
  s.counters.steps = 1u << 20, s.counters.density_iterations = 3, s.counters.divergence_iterations = 4, s.counters.density_unconverged = 5;
  s.counters.divergence_unconverged = 6, s.counters.corrections = 7, s.counters.dt_clamped_to_min = 8;
  s.counters.dt_sum = 1.5, s.counters.density_error = 2.5e-4, s.counters.max_density_error = 4.9e-4, s.counters.divergence_error = 1e-5;
  s.counters.min_dt_used = 1e-4, s.counters.max_dt_used = 5e-3;
  s.counters.retries = 9, s.counters.step_cap = 1.25e-3;
  s.ids = {2, 0, 1};
  s.positions = {Vec3f(1, 2, 3), Vec3f(-0.0f, 1e-30f, 7), Vec3f(0.1f, 0.2f, 0.3f)};
  s.velocities = {Vec3f(4, 5, 6), Vec3f(-1, -2, -3), Vec3f(0, 0, 0)};
  s.density_warm = {0.5f, 0.25f, 0.125f};
  s.divergence_warm = {1, 2, 3};
  const testing::TempDir temp;
  const fs::path file = temp / "roundtrip.spr";
  write_restart_state(file, s);
  // Header 184 bytes, 3 x (4 + 12 + 12 + 4 + 4) bytes of particles, 4 bytes of CRC.
  EXPECT_EQ(fs::file_size(file), 184u + 3u * 36u + 4u);
  const FluidRestartState r = read_restart_state(file);
  EXPECT_EQ(r.frame, 42);
  EXPECT_EQ(r.time, s.time);
  EXPECT_EQ(r.dt_prev, s.dt_prev);
  EXPECT_EQ(r.particle_radius, s.particle_radius);
  EXPECT_EQ(r.digest, s.digest);
  EXPECT_EQ(r.counters.steps, s.counters.steps);
  EXPECT_EQ(r.counters.density_iterations, 3u);
  EXPECT_EQ(r.counters.divergence_iterations, 4u);
  EXPECT_EQ(r.counters.density_unconverged, 5u);
  EXPECT_EQ(r.counters.divergence_unconverged, 6u);
  EXPECT_EQ(r.counters.corrections, 7u);
  EXPECT_EQ(r.counters.dt_clamped_to_min, 8u);
  EXPECT_EQ(r.counters.dt_sum, 1.5);
  EXPECT_EQ(r.counters.density_error, 2.5e-4);
  EXPECT_EQ(r.counters.max_density_error, 4.9e-4);
  EXPECT_EQ(r.counters.divergence_error, 1e-5);
  EXPECT_EQ(r.counters.min_dt_used, 1e-4);
  EXPECT_EQ(r.counters.max_dt_used, 5e-3);
  EXPECT_EQ(r.counters.retries, 9u);
  EXPECT_EQ(r.counters.step_cap, 1.25e-3);
  EXPECT_EQ(r.ids, s.ids);
  EXPECT_TRUE(same_bytes(r.positions, s.positions));  // -0 and denormals too
  EXPECT_TRUE(same_bytes(r.velocities, s.velocities));
  EXPECT_EQ(r.density_warm, s.density_warm);
  EXPECT_EQ(r.divergence_warm, s.divergence_warm);

  // Without warm start the arrays are left out (flags bit 0 clear).
  s.density_warm.clear(), s.divergence_warm.clear();
  write_restart_state(file, s);
  EXPECT_EQ(fs::file_size(file), 184u + 3u * 28u + 4u);
  EXPECT_TRUE(read_restart_state(file).density_warm.empty());
}

std::string error_reading(const fs::path& file) {
  try {
    read_restart_state(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FluidRestart, CorruptFilesAreRefusedNamingTheFile) {
  FluidSolver solver = column(false, false).make();
  solver.advance_to(0.01);
  const testing::TempDir temp;
  const fs::path file = temp / "corrupt.spr";
  write_restart_state(file, solver.restart_state(1));
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto rewrite = [&](const std::string& content) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << content;
  };
  std::string flipped = bytes;
  flipped[200] ^= 0x10;  // inside the positions
  rewrite(flipped);
  EXPECT_NE(error_reading(file).find("CRC-32 mismatch"), std::string::npos) << error_reading(file);
  rewrite(bytes.substr(0, bytes.size() - 10));
  EXPECT_NE(error_reading(file).find(file.string()), std::string::npos);
  rewrite("SPUMEFL1" + bytes.substr(8));
  EXPECT_NE(error_reading(file).find("not a spume restart file"), std::string::npos) << error_reading(file);
  fs::remove(file);
  EXPECT_NE(error_reading(file).find("no such file"), std::string::npos) << error_reading(file);
}

std::string error_restoring(FluidSolver& solver, const FluidRestartState& s) {
  try {
    solver.restore(s);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FluidRestart, StatesThatDoNotFitAreRefusedAndLeaveTheSolverUntouched) {
  FluidSolver source = column(false, false).make();
  source.advance_to(0.02);
  const FluidRestartState good = source.restart_state(1);

  FluidSolver target = column(false, false).make();
  const FluidFrame before = target.frame(0);
  FluidRestartState bad = good;
  bad.ids.pop_back(), bad.positions.pop_back(), bad.velocities.pop_back();
  EXPECT_NE(error_restoring(target, bad).find("1279 particles; the scene makes 1280"), std::string::npos);
  bad = good;
  bad.ids[0] = bad.ids[1];
  EXPECT_NE(error_restoring(target, bad).find("not a permutation"), std::string::npos);
  bad = good;
  bad.particle_radius = 0.02f;
  EXPECT_NE(error_restoring(target, bad).find("particle radius"), std::string::npos);
  FluidSolver warm = column(false, true).make();
  EXPECT_NE(error_restoring(warm, good).find("warm_start"), std::string::npos);
  EXPECT_EQ(target.time(), 0.0);
  EXPECT_TRUE(same_bytes(target.frame(0).positions, before.positions));

  // A dynamic body's Bullet state is not in the file: refused.
  Scene with_body = column(false, false);
  Solid ball;
  ball.kind = Solid::Kind::Sphere;
  ball.center = Vec3f(0.3f, 0.3f, 0.08f);
  ball.radius = 0.04f;
  ball.dynamics.enabled = true;
  ball.dynamics.density = 500.0f;
  with_body.solids = SolidSet({tank(), ball});
  FluidSolver bodies = with_body.make();
  EXPECT_NE(error_restoring(bodies, bodies.restart_state(0)).find("dynamic solids"), std::string::npos);
}

}  // namespace
}  // namespace spume
