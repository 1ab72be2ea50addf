// Bubble drag k_d from 0 to 1e6 in both modes: the paper's explicit update is refused past k_d = 1
// (it overshoots, then diverges past 2), the exponential mode stays exact and converges to the
// fluid velocity (plus the buoyant terminal rise) for any k_d.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/stability/stability_support.h"

namespace spume {
namespace {

using stability::error_of;

const double kDrags[] = {0.0, 0.5, 1.0, 1.5, 2.0, 10.0, 1e6};

Json drag_keys(const char* mode, double kd, double buoyancy) {
  return {{"bubble_drag", mode}, {"drag", kd}, {"buoyancy", buoyancy}, {"k_ta", 0}, {"k_wc", 0}};
}

TEST(StabilityDrag, PaperModeRefusesDragAboveOneNamingKeyValueAndRange) {
  for (double kd : kDrags) {
    const Json keys = drag_keys("paper", kd, 2.0);
    if (kd <= 1.0) {
      EXPECT_NO_THROW(stability::setup_with(0.02f, keys)) << kd;
      continue;
    }
    const std::string message = error_of([&] { stability::setup_with(0.02f, keys); });
    EXPECT_NE(message.find("/drag"), std::string::npos) << message;
    EXPECT_NE(message.find(str("value ", kd)), std::string::npos) << message;
    EXPECT_NE(message.find("allowed [0, 1]"), std::string::npos) << message;
  }
}

TEST(StabilityDrag, ExponentialModeAcceptsEveryDrag) {
  for (double kd : kDrags) EXPECT_NO_THROW(stability::setup_with(0.02f, drag_keys("exponential", kd, 2.0))) << kd;
}

// One bubble at the centre of a 0.6 m block of fluid translating at u; `frames` frames at 50 fps, one
// diffuse step each. Returns the bubble's velocity after each step.
std::vector<Vec3f> bubble_velocities(const DiffuseSetup& setup, const Vec3f& u, int frames) {
  const float r = setup.fluid.particle_radius;
  const auto fluid = stability::translating_block(Vec3f(0, 0, 0), Vec3f(0.6f, 0.6f, 0.6f), r, u, 1.0 / 50, frames);
  DiffuseSimulator sim(setup);
  sim.set_particles(stability::diffuse_at({Vec3f(0.3f, 0.3f, 0.3f)}, DiffuseType::Bubble));
  std::vector<Vec3f> v;
  for (int k = 0; k + 1 < frames; ++k) {
    sim.process_frame(fluid[k], &fluid[k + 1], [&](const DiffuseFrame& f, const FrameStats&) {
      EXPECT_TRUE(stability::all_finite(f));
      EXPECT_EQ(f.size(), 1u);
      if (f.size() == 1) {
        EXPECT_EQ(f.types[0], DiffuseType::Bubble) << "frame " << k;
      }
    });
    EXPECT_TRUE(stability::all_finite(sim.particles()));
    v.push_back(sim.particles().velocities.at(0));
  }
  return v;
}

TEST(StabilityDrag, ExponentialModeFollowsTheClosedFormAndConvergesToTheFluid) {
  // dv/dt = L + (u - v) / tau, tau = reference_step / k_d, v(0) = 0, L = k_b * 9.81 up:
  // v(t) = u + tau L - (u + tau L) e^{-t/tau}; without drag v(t) = t L.
  const Vec3f u(0.5f, 0.0f, -0.25f);
  const double dt = 1.0 / 50;
  for (double buoyancy : {0.0, 2.0})
    for (double kd : kDrags) {
      const DiffuseSetup setup = stability::setup_with(0.02f, drag_keys("exponential", kd, buoyancy));
      const double lift = buoyancy * 9.81, ref = setup.params.drag_reference_step;
      const auto v = bubble_velocities(setup, u, 6);
      for (size_t n = 0; n < v.size(); ++n) {
        const double t = double(n + 1) * dt;
        Eigen::Vector3d expected;
        if (kd == 0.0) {
          expected = Eigen::Vector3d(0, t * lift, 0);
        } else {
          const double tau = ref / kd, e = std::exp(-t / tau);
          const Eigen::Vector3d w = u.cast<double>() + Eigen::Vector3d(0, tau * lift, 0);
          expected = w - w * e;
        }
        EXPECT_NEAR((v[n].cast<double>() - expected).norm(), 0.0, 1e-4 + 1e-5 * expected.norm())
            << "k_d " << kd << " buoyancy " << buoyancy << " step " << n << ": " << v[n].transpose();
      }
      if (kd >= 1.0 && buoyancy == 0.0) {  // e^{-5} or less left of the initial gap
        EXPECT_LT((v.back() - u).norm(), 1.001f * std::exp(-5.0f) * u.norm() + 1e-5f) << kd;
      }
    }
}

TEST(StabilityDrag, PaperModeFollowsItsRecurrenceUpToDragOne) {
  // v_{n+1} = v_n + dt L + k_d (u - v_n): the gap to v* = u + dt L / k_d shrinks by (1 - k_d) a step.
  const Vec3f u(0.5f, 0.0f, -0.25f);
  const double dt = 1.0 / 50;
  for (double buoyancy : {0.0, 2.0})
    for (double kd : {0.0, 0.5, 1.0}) {
      const DiffuseSetup setup = stability::setup_with(0.02f, drag_keys("paper", kd, buoyancy));
      const Eigen::Vector3d L(0, buoyancy * 9.81, 0);
      const auto v = bubble_velocities(setup, u, 6);
      for (size_t n = 0; n < v.size(); ++n) {
        const double steps = double(n + 1);
        Eigen::Vector3d expected;
        if (kd == 0.0) {
          expected = steps * dt * L;
        } else {
          const Eigen::Vector3d fixed = u.cast<double>() + dt * L / kd;
          expected = fixed - fixed * std::pow(1.0 - kd, steps);
        }
        EXPECT_NEAR((v[n].cast<double>() - expected).norm(), 0.0, 1e-4 + 1e-5 * expected.norm())
            << "k_d " << kd << " buoyancy " << buoyancy << " step " << n;
      }
    }
}

// Every drag in a colliding-blocks run with emission on: thousands of bubbles born inside the impact,
// each step finite and inside the domain, for 20 frames.
TEST(StabilityDrag, EveryDragInACollisionFull) {
  const auto fluid = stability::colliding_blocks(0.02f, 0.3f, 2.0f, 1.0 / 50, 20);
  for (const char* mode : {"paper", "exponential"})
    for (double kd : kDrags) {
      if (std::string(mode) == "paper" && kd > 1.0) continue;  // refused, above
      DiffuseSetup setup = stability::setup_with(0.02f, {{"bubble_drag", mode}, {"drag", kd}});
      setup.domain.min = Vec3f(-2, -1, -1), setup.domain.max = Vec3f(2, 3, 2);
      DiffuseSimulator sim(setup);
      const auto r = stability::run_checked(sim, fluid);
      EXPECT_GT(r.generated, 1000u) << mode << " " << kd;
      // Without drag a bubble only accelerates upwards (k_b g) and leaves the fluid: none remain.
      if (kd > 0.0) {
        EXPECT_GT(sim.particles().count_by_type()[size_t(DiffuseType::Bubble)], 100u) << mode << " " << kd;
      }
    }
}

}  // namespace
}  // namespace spume
