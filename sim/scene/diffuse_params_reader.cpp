#include "diffuse_params_reader.h"

#include <cmath>

#include "core/error.h"

namespace spume {
namespace {

ClampRange read_range(const ParamReader& r, const std::string& key, double lo, double hi) {
  const auto [a, b] = r.range(key, {lo, hi});
  if (a < 0.0) r.fail_at(key, str("min ", a, " must be >= 0: the quantity it clamps is never negative"));
  return {float(a), float(b)};
}

}  // namespace

DiffuseParams read_diffuse_params(const ParamReader& d, const FluidSequenceInfo& fluid, const Vec3f& gravity) {
  // Froude similarity to the reference radius (MODEL.md §8.9).
  const double s = double(fluid.particle_radius) / kDefaultsReferenceRadius;
  const double velocity = std::sqrt(s), time = std::sqrt(s), rate = 1.0 / std::sqrt(s);
  const double reference_mass = double(fluid.rest_density) * std::pow(2.0 * kDefaultsReferenceRadius, 3.0);
  const double energy = double(fluid.uniform_mass()) / reference_mass * s;

  DiffuseParams p;
  // Formation (MODEL.md §1). Reference values for r = 0.02 m water: trapped air from 2 m/s of
  // approach summed over the neighbourhood, crests from the paper's curvature band, and the kinetic
  // clamp from 0.7 to 2.5 m/s of particle speed (0.5 m v^2 with m = 0.064 kg). Rates: 300 samples/s
  // at full potential, tuned on scenes/wave.json (1000 turned the whole surface white within a
  // second, ~30 diffuse particles per fluid particle; 300 gives ~3, foam in patches and streaks).
  p.trapped_air = read_range(d, "tau_ta", 2.0 * velocity, 8.0 * velocity);
  p.wave_crest = read_range(d, "tau_wc", 2.0, 8.0);
  p.kinetic = read_range(d, "tau_k", 0.0157 * energy, 0.2 * energy);
  p.k_ta = float(d.non_negative("k_ta", 300.0 * rate));
  p.k_wc = float(d.non_negative("k_wc", 300.0 * rate));
  const auto [life_lo, life_hi] = d.range("lifetime", {1.5 * time, 4.0 * time});
  if (life_lo <= 0.0) d.fail_at("lifetime", str("min ", life_lo, " must be > 0 s"));
  p.lifetime_min = float(life_lo), p.lifetime_max = float(life_hi);
  p.surface_threshold = float(d.number_in("surface_threshold", 0.3, 0.0, 10.0));
  p.surface_neighbour_fraction = float(d.number_in("surface_neighbour_fraction", 0.75, 0.0, 10.0));

  // Classification (MODEL.md §3, §8.11).
  p.spray_below = float(d.number_in("spray_below", 6.0, 0.0, 1e4));
  p.bubble_above = float(d.number_in("bubble_above", 20.0, 0.0, 1e4));
  if (!(p.spray_below <= p.bubble_above))
    d.fail_at("bubble_above", str("value ", p.bubble_above, " must be >= spray_below (", p.spray_below, ")"));
  p.hysteresis = float(d.number_in("hysteresis", 1.0, 0.0, 100.0));
  p.count_solids = d.boolean("count_solids", true);

  // Advection (MODEL.md §4, §8.4-8.6).
  p.gravity = gravity;
  p.buoyancy = float(d.number_in("buoyancy", 2.0, 0.0, 1e3));
  p.bubble_drag = d.choice("bubble_drag", "exponential", {"exponential", "paper"}) == "paper" ? BubbleDrag::Paper
                                                                                              : BubbleDrag::Exponential;
  if (p.bubble_drag == BubbleDrag::Paper) {
    // v += k_d (u - v) per step overshoots for k_d > 1 and diverges for k_d > 2 (MODEL.md §8.4).
    p.drag = float(d.number_in("drag", 0.5, 0.0, 1.0));
  } else {
    p.drag = float(d.non_negative("drag", 0.5));
  }
  p.drag_reference_step = float(d.positive("drag_reference_step", 0.02 * time));
  p.spray_integrator = d.choice("spray_integrator", "exact", {"exact", "euler_cromer"}) == "exact"
                           ? SprayIntegrator::Exact
                           : SprayIntegrator::EulerCromer;
  p.foam_velocity = d.choice("foam_velocity", "fluid", {"fluid", "stale"}) == "fluid" ? FoamVelocity::Fluid
                                                                                      : FoamVelocity::Stale;
  p.substeps = int(d.integer_in("substeps", 1, 1, 64));
  p.seed = uint64_t(d.integer_in("seed", 1, 0, std::numeric_limits<long>::max()));
  if (d.has("max_particles")) p.max_particles = uint64_t(d.integer_in("max_particles", 0, 0, long(1) << 40));
  return p;
}

Json diffuse_params_to_json(const DiffuseParams& p) {
  auto range = [](const ClampRange& r) { return Json::array({r.lo, r.hi}); };
  Json j = {
      {"tau_ta", range(p.trapped_air)},
      {"tau_wc", range(p.wave_crest)},
      {"tau_k", range(p.kinetic)},
      {"k_ta", p.k_ta},
      {"k_wc", p.k_wc},
      {"lifetime", Json::array({p.lifetime_min, p.lifetime_max})},
      {"surface_threshold", p.surface_threshold},
      {"surface_neighbour_fraction", p.surface_neighbour_fraction},
      {"spray_below", p.spray_below},
      {"bubble_above", p.bubble_above},
      {"hysteresis", p.hysteresis},
      {"count_solids", p.count_solids},
      {"buoyancy", p.buoyancy},
      {"drag", p.drag},
      {"drag_reference_step", p.drag_reference_step},
      {"bubble_drag", p.bubble_drag == BubbleDrag::Paper ? "paper" : "exponential"},
      {"spray_integrator", p.spray_integrator == SprayIntegrator::Exact ? "exact" : "euler_cromer"},
      {"foam_velocity", p.foam_velocity == FoamVelocity::Fluid ? "fluid" : "stale"},
      {"substeps", p.substeps},
      {"seed", p.seed},
  };
  if (p.max_particles) j["max_particles"] = *p.max_particles;
  return j;
}

}  // namespace spume
