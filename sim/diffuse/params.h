#pragma once
// Every parameter of the diffuse model, in SI units, as plain typed values. The keys, their defaults
// and ranges are declared once, in keys/diffuse_keys.h; the defaults here are those declarations at
// the reference radius r0 = 0.02 m, and the scene reader (scene/diffuse_params_reader.cpp) carries
// them to the scene's radius.
#include <cstdint>
#include <optional>
#include <string_view>

#include "sim/core/vec.h"
#include "sim/keys/diffuse_keys.h"
#include "sim/keys/scene_keys.h"

namespace spume {

struct ClampRange {
  float lo = 0.0f, hi = 1.0f;  // lo < hi always (validated)
};

enum class BubbleDrag { Paper, Exponential };       // MODEL.md §4 as printed | §8.4 exact integration
enum class SprayIntegrator { EulerCromer, Exact };  // MODEL.md §4 as printed | §8.6 exact ballistic
enum class FoamVelocity { Stale, Fluid };           // MODEL.md §4 as printed | §8.5 foam carries the fluid's

namespace diffuse_default {
constexpr float of(const KeySpec& k, int i = 0) { return float(k.value[size_t(i)]); }
constexpr ClampRange clamp(const KeySpec& k) { return {of(k, 0), of(k, 1)}; }
}  // namespace diffuse_default

struct DiffuseParams {
  // Formation (MODEL.md §1).
  ClampRange trapped_air = diffuse_default::clamp(keys::diffuse::tau_ta);  // m/s, on v_diff
  ClampRange wave_crest = diffuse_default::clamp(keys::diffuse::tau_wc);   // on the curvature sum
  ClampRange kinetic = diffuse_default::clamp(keys::diffuse::tau_k);       // J, on E_k
  float crest_support = diffuse_default::of(keys::diffuse::crest_support);  // Eqs. 4-6 radius, in h
  float k_ta = diffuse_default::of(keys::diffuse::k_ta);                   // 1/s
  float k_wc = diffuse_default::of(keys::diffuse::k_wc);                   // 1/s
  float lifetime_min = diffuse_default::of(keys::diffuse::lifetime, 0);    // s
  float lifetime_max = diffuse_default::of(keys::diffuse::lifetime, 1);    // s
  // A fluid particle is a surface particle when |grad c| * h reaches this; below it its normal is
  // undefined and it contributes no crest potential (MODEL.md §8.10) ...
  float surface_threshold = diffuse_default::of(keys::diffuse::surface_threshold);
  // ... and has fewer neighbours within h than this fraction of a full neighbourhood (4/3 pi h^3 / V).
  // The gradient alone is not enough: in a disordered fluid its noise inside reaches half the value
  // at the surface, while the neighbour count drops by a quarter only in the outermost layer.
  float surface_neighbour_fraction = diffuse_default::of(keys::diffuse::surface_neighbour_fraction);

  // Classification (MODEL.md §3), on the fluid-neighbour count within h (scaled where walls are wet).
  float spray_below = diffuse_default::of(keys::diffuse::spray_below);
  float bubble_above = diffuse_default::of(keys::diffuse::bubble_above);
  float hysteresis = diffuse_default::of(keys::diffuse::hysteresis);
  bool count_solids = keys::diffuse::count_solids.value[0] != 0.0;

  // Advection (MODEL.md §4).
  Vec3f gravity = Vec3f(diffuse_default::of(keys::scene::gravity, 0), diffuse_default::of(keys::scene::gravity, 1),
                        diffuse_default::of(keys::scene::gravity, 2));  // m/s^2
  float buoyancy = diffuse_default::of(keys::diffuse::buoyancy);         // k_b, multiples of -g
  float drag = diffuse_default::of(keys::diffuse::drag);                 // k_d per reference step
  float drag_reference_step = diffuse_default::of(keys::diffuse::drag_reference_step);  // s
  BubbleDrag bubble_drag = BubbleDrag::Exponential;
  SprayIntegrator spray_integrator = SprayIntegrator::Exact;
  FoamVelocity foam_velocity = FoamVelocity::Fluid;

  int substeps = int(keys::diffuse::substeps.value[0]);  // diffuse steps per frame interval
  uint64_t seed = uint64_t(keys::diffuse::seed.value[0]);
  std::optional<uint64_t> max_particles;                 // emission budget (none)
};

// The enums' defaults above are the declared choices' first entries.
static_assert(std::string_view(keys::diffuse::bubble_drag.choices).starts_with("exponential|"));
static_assert(std::string_view(keys::diffuse::spray_integrator.choices).starts_with("exact|"));
static_assert(std::string_view(keys::diffuse::foam_velocity.choices).starts_with("fluid|"));

}  // namespace spume
