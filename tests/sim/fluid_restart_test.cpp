// The solver's restart state (fluid/restart_state.h): a solver restored from a saved state steps to
// the same bytes as the solver that saved it, for any thread count, with a moving solid and with
// warm start, and with dynamic bodies (floating, resting on the floor, falling in); the file
// round-trips every field exactly and refuses corrupt copies; states that do not fit the solver are
// refused.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/fluid/solver.h"
#include "sim/io/crc32.h"
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
    ASSERT_EQ(straight.body_poses().size(), resumed.body_poses().size());
    for (size_t i = 0; i < straight.body_poses().size(); ++i) {
      const BodyPose &p = straight.body_poses()[i], &q = resumed.body_poses()[i];
      EXPECT_EQ(p.position, q.position) << "body " << i << ", t = " << t;
      EXPECT_EQ(p.orientation.coeffs(), q.orientation.coeffs()) << "body " << i << ", t = " << t;
      EXPECT_EQ(p.velocity, q.velocity) << "body " << i << ", t = " << t;
      EXPECT_EQ(p.angular_velocity, q.angular_velocity) << "body " << i << ", t = " << t;
    }
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

// The column with three bodies: a light flat box in the front's path (its inertia depends on its
// orientation), a dense one resting on the floor (it starts within the floor's skin), and a ball
// falling in from above.
Scene column_with_bodies() {
  Scene s = column(false, false);
  Solid light, dense, ball;
  light.kind = dense.kind = Solid::Kind::Box;
  light.min = Vec3f(0.2f, 0.0f, 0.04f), light.max = Vec3f(0.28f, 0.03f, 0.1f);
  light.dynamics.enabled = true, light.dynamics.density = 500.0f;
  dense.min = Vec3f(0.32f, 0.0f, 0.05f), dense.max = Vec3f(0.37f, 0.05f, 0.1f);
  dense.dynamics.enabled = true, dense.dynamics.density = 3000.0f;
  ball.kind = Solid::Kind::Sphere;
  ball.center = Vec3f(0.1f, 0.34f, 0.08f);
  ball.radius = 0.03f;
  ball.dynamics.enabled = true, ball.dynamics.density = 800.0f;
  s.solids = SolidSet({tank(), light, dense, ball});
  return s;
}

TEST(FluidRestart, RestoredSolverWithDynamicBodiesContinuesByteIdentically) {
  const Scene scene = column_with_bodies();
  expect_continuation_identical(scene, 0.1, 0.2, 2);
  // The bodies did move after the save: the ball fell into the water and the front reached the box.
  FluidSolver solver = scene.make();
  solver.advance_to(0.1);
  const std::vector<BodyPose> at_save = solver.body_poses();
  solver.advance_to(0.2);
  for (size_t b : {size_t(0), size_t(2)})
    EXPECT_GT((solver.body_poses()[b].position - at_save[b].position).norm(), 0.002) << "body " << b;
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
  BodyPose a, b;
  a.solid = 3, a.position = Vec3f(0.5f, -0.0f, 1e-30f), a.orientation = Quatf(0.5f, -0.5f, 0.5f, 0.5f);
  a.velocity = Vec3f(1, 2, 3), a.angular_velocity = Vec3f(-4, 5, -6);
  b.solid = 7, b.position = Vec3f(1.0f / 3.0f, 2, 3);
  s.bodies = {a, b};
  const testing::TempDir temp;
  const fs::path file = temp / "roundtrip.spr";
  write_restart_state(file, s);
  // Header 184 bytes, 3 x (4 + 12 + 12 + 4 + 4) bytes of particles, a body count and 2 x 56 bytes of
  // bodies, 4 bytes of CRC.
  EXPECT_EQ(fs::file_size(file), 184u + 3u * 36u + 4u + 2u * 56u + 4u);
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
  ASSERT_EQ(r.bodies.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const BodyPose &p = s.bodies[i], &q = r.bodies[i];
    EXPECT_EQ(q.solid, p.solid);
    EXPECT_TRUE(std::memcmp(q.position.data(), p.position.data(), 12) == 0) << i;  // -0 and denormals too
    EXPECT_EQ(q.orientation.coeffs(), p.orientation.coeffs()) << i;
    EXPECT_EQ(q.velocity, p.velocity) << i;
    EXPECT_EQ(q.angular_velocity, p.angular_velocity) << i;
  }

  // Without warm start the arrays are left out (flags bit 0 clear); without bodies, the count is 0.
  s.density_warm.clear(), s.divergence_warm.clear(), s.bodies.clear();
  write_restart_state(file, s);
  EXPECT_EQ(fs::file_size(file), 184u + 3u * 28u + 4u + 4u);
  EXPECT_TRUE(read_restart_state(file).density_warm.empty());
  EXPECT_TRUE(read_restart_state(file).bodies.empty());

  // A version 2 file (an older spume's: no body section) reads as a state without bodies.
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::string v2 = bytes.substr(0, bytes.size() - 8);  // without the body count and the CRC
  v2[8] = 2;
  const uint32_t crc = crc32_update(crc32_start(), v2.data(), v2.size());
  v2.append(reinterpret_cast<const char*>(&crc), 4);
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << v2;
  }
  const FluidRestartState old = read_restart_state(file);
  EXPECT_TRUE(old.bodies.empty());
  EXPECT_EQ(old.ids, s.ids);
  EXPECT_TRUE(same_bytes(old.velocities, s.velocities));
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

  // A state of a scene without bodies does not fit one with bodies, nor bodies of other solids.
  FluidSolver bodies = column_with_bodies().make();
  EXPECT_NE(error_restoring(bodies, good).find("the saved state has 0 dynamic bodies; the scene has 3"), std::string::npos);
  bad = bodies.restart_state(0);
  bad.bodies[1].solid = 1;
  EXPECT_NE(error_restoring(bodies, bad).find("body 1 is solid 1; the scene's is solid 2"), std::string::npos);
}

}  // namespace
}  // namespace spume
