// Analytic cases of the diffuse integrators, with closed-form answers.
//   spray:  x(t) = x0 + v0 t + g t^2 / 2
//   bubble: dv/dt = -k_b g + (u - v) / tau, tau = reference_step / k_d, uniform fluid velocity u:
//           v(t) = w + (v0 - w) e^{-t/tau}, x(t) = x0 + w t + (v0 - w) tau (1 - e^{-t/tau}), w = u - k_b g tau
// The paper's bubble update is compared with the same ODE: it relaxes a fixed fraction k_d per step,
// which equals the ODE's rate only at dt = reference_step (MODEL.md §8.4).
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "sim/diffuse/advection.h"
#include "render/app/report/diffuse_runs.h"

namespace spume::report {
namespace {

// Particles spread a little so the batch is not one value repeated; particle 0 is the measured one.
void start(std::vector<Vec3f>& x, std::vector<Vec3f>& v, const Vec3f& v0, int n) {
  x.assign(size_t(n), Vec3f::Zero());
  v.resize(size_t(n));
  for (int i = 0; i < n; ++i) v[size_t(i)] = v0 + Vec3f(1e-6f * float(i % 97), 0, 0);
}

}  // namespace

std::vector<AnalyticRun> analytic_runs(const DiffuseParams& scene_params, double fps, double horizon, int particles) {
  const int frames = std::max(1, int(std::lround(horizon * fps)));
  const double T = frames / fps;
  const Vec3d g = scene_params.gravity.cast<double>();
  const Vec3f spray_v0(1.0f, 3.0f, 0.5f), u(0.3f, 0.0f, 0.0f);
  const Vec3d spray_exact = spray_v0.cast<double>() * T + 0.5 * g * T * T;
  const double tau = scene_params.drag_reference_step / scene_params.drag;
  const Vec3d w = u.cast<double>() - scene_params.buoyancy * g * tau;
  // v0 = 0: x(T) = w T - w tau (1 - e^{-T/tau}).
  const Vec3d bubble_exact = w * T - w * tau * (1.0 - std::exp(-T / tau));

  struct Integrator {
    std::string name;
    bool spray;
    SprayIntegrator spray_kind;
    BubbleDrag drag;
  };
  const std::vector<Integrator> integrators = {
      {"spray euler_cromer", true, SprayIntegrator::EulerCromer, BubbleDrag::Exponential},
      {"spray exact", true, SprayIntegrator::Exact, BubbleDrag::Exponential},
      {"bubble paper", false, SprayIntegrator::Exact, BubbleDrag::Paper},
      {"bubble exponential", false, SprayIntegrator::Exact, BubbleDrag::Exponential}};
  if (scene_params.drag > 1.0f)
    fail("diffuse study: diffuse.drag = ", scene_params.drag, " is outside the paper mode's [0, 1]");

  std::vector<AnalyticRun> out;
  std::vector<Vec3f> x, v;
  for (const Integrator& it : integrators) {
    std::vector<int> counts = kSubsteps;
    counts.push_back(kReferenceSubsteps);
    std::vector<Vec3d> end;
    std::vector<double> ms;
    for (int n : counts) {
      start(x, v, it.spray ? spray_v0 : Vec3f::Zero(), particles);
      const float dt = float(1.0 / (fps * n));
      DiffuseParams p = scene_params;
      p.bubble_drag = it.drag;
      const BubbleStep bubble = bubble_step(p, dt);
      const Stopwatch t0;
      for (int s = 0; s < frames * n; ++s)
        for (size_t i = 0; i < x.size(); ++i) {
          if (it.spray) advance_spray(x[i], v[i], scene_params.gravity, dt, it.spray_kind);
          else advance_bubble(x[i], v[i], u, bubble);
        }
      ms.push_back(t0.milliseconds() / frames * 1e6 / particles);
      end.push_back(x[0].cast<double>());
    }
    const Vec3d exact = it.spray ? spray_exact : bubble_exact;
    for (size_t k = 0; k < counts.size(); ++k)
      out.push_back({it.name, counts[k], (end[k] - end.back()).norm(), (end[k] - exact).norm(), ms[k]});
  }
  return out;
}

}  // namespace spume::report
