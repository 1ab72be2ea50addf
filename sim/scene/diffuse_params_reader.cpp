#include "sim/scene/diffuse_params_reader.h"

#include <cmath>

#include "sim/core/error.h"
#include "sim/keys/diffuse_keys.h"

namespace spume {
namespace {

namespace k = keys::diffuse;

ClampRange read_clamp(const ParamReader& d, const KeySpec& key, double r, double mass_ratio) {
  const auto [a, b] = d.range(key, r, mass_ratio);
  return {float(a), float(b)};
}

}  // namespace

DiffuseParams read_diffuse_params(const ParamReader& d, const FluidSequenceInfo& fluid, const Vec3f& gravity) {
  const double r = fluid.particle_radius;
  // Froude similarity of energies: the particle's mass over a water particle of radius r0.
  const double reference_mass = double(fluid.rest_density) * std::pow(2.0 * kDefaultsReferenceRadius, 3.0);
  const double mass_ratio = double(fluid.uniform_mass()) / reference_mass;

  DiffuseParams p;
  p.trapped_air = read_clamp(d, k::tau_ta, r, mass_ratio);
  p.wave_crest = read_clamp(d, k::tau_wc, r, mass_ratio);
  p.kinetic = read_clamp(d, k::tau_k, r, mass_ratio);
  p.crest_support = float(d.number(k::crest_support));
  p.k_ta = float(d.number(k::k_ta, r));
  p.k_wc = float(d.number(k::k_wc, r));
  const auto [life_lo, life_hi] = d.range(k::lifetime, r);
  p.lifetime_min = float(life_lo), p.lifetime_max = float(life_hi);
  p.surface_threshold = float(d.number(k::surface_threshold));
  p.surface_neighbour_fraction = float(d.number(k::surface_neighbour_fraction));

  p.spray_below = float(d.number(k::spray_below));
  p.bubble_above = float(d.number(k::bubble_above));
  if (!(p.spray_below <= p.bubble_above))
    d.fail_at("bubble_above", str("value ", p.bubble_above, " must be >= spray_below (", p.spray_below, ")"));
  p.hysteresis = float(d.number(k::hysteresis));
  p.count_solids = d.boolean(k::count_solids);

  p.gravity = gravity;
  p.buoyancy = float(d.number(k::buoyancy));
  p.bubble_drag = d.choice(k::bubble_drag) == "paper" ? BubbleDrag::Paper : BubbleDrag::Exponential;
  p.drag = float(d.number(k::drag));
  // v += k_d (u - v) per step overshoots for k_d > 1 and diverges for k_d > 2 (MODEL.md §8.4).
  if (p.bubble_drag == BubbleDrag::Paper && p.drag > 1.0f)
    d.fail_at("drag", str("value ", p.drag, " is out of range for bubble_drag \"paper\"; allowed [0, 1] (the "
                          "update as printed overshoots above 1 and diverges above 2; \"exponential\" takes any)"));
  p.drag_reference_step = float(d.number(k::drag_reference_step, r));
  p.spray_integrator = d.choice(k::spray_integrator) == "exact" ? SprayIntegrator::Exact : SprayIntegrator::EulerCromer;
  p.foam_velocity = d.choice(k::foam_velocity) == "fluid" ? FoamVelocity::Fluid : FoamVelocity::Stale;
  p.substeps = int(d.integer(k::substeps));
  p.seed = uint64_t(d.integer(k::seed));
  if (d.has(k::max_particles.name())) p.max_particles = uint64_t(d.integer(k::max_particles));
  return p;
}

Json diffuse_params_to_json(const DiffuseParams& p) {
  auto range = [](float lo, float hi) { return Json::array({lo, hi}); };
  Json j;
  j[k::tau_ta.name()] = range(p.trapped_air.lo, p.trapped_air.hi);
  j[k::tau_wc.name()] = range(p.wave_crest.lo, p.wave_crest.hi);
  j[k::tau_k.name()] = range(p.kinetic.lo, p.kinetic.hi);
  j[k::crest_support.name()] = p.crest_support;
  j[k::k_ta.name()] = p.k_ta;
  j[k::k_wc.name()] = p.k_wc;
  j[k::lifetime.name()] = range(p.lifetime_min, p.lifetime_max);
  j[k::surface_threshold.name()] = p.surface_threshold;
  j[k::surface_neighbour_fraction.name()] = p.surface_neighbour_fraction;
  j[k::spray_below.name()] = p.spray_below;
  j[k::bubble_above.name()] = p.bubble_above;
  j[k::hysteresis.name()] = p.hysteresis;
  j[k::count_solids.name()] = p.count_solids;
  j[k::buoyancy.name()] = p.buoyancy;
  j[k::drag.name()] = p.drag;
  j[k::drag_reference_step.name()] = p.drag_reference_step;
  j[k::bubble_drag.name()] = p.bubble_drag == BubbleDrag::Paper ? "paper" : "exponential";
  j[k::spray_integrator.name()] = p.spray_integrator == SprayIntegrator::Exact ? "exact" : "euler_cromer";
  j[k::foam_velocity.name()] = p.foam_velocity == FoamVelocity::Fluid ? "fluid" : "stale";
  j[k::substeps.name()] = p.substeps;
  j[k::seed.name()] = p.seed;
  if (p.max_particles) j[k::max_particles.name()] = *p.max_particles;
  return j;
}

}  // namespace spume
