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

// The declared default [min, max] of a Range key.
constexpr ClampRange declared_clamp(const KeySpec& k) { return {declared_float(k, 0), declared_float(k, 1)}; }

struct DiffuseParams {
  // Formation (MODEL.md §1).
  ClampRange trapped_air = declared_clamp(keys::diffuse::tau_ta);      // m/s, on v_diff
  ClampRange wave_crest = declared_clamp(keys::diffuse::tau_wc);       // on the curvature sum
  ClampRange kinetic = declared_clamp(keys::diffuse::tau_k);           // J, on E_k
  float crest_support = declared_float(keys::diffuse::crest_support);  // Eqs. 4-6 radius, in h
  float k_ta = declared_float(keys::diffuse::k_ta);                    // 1/s
  float k_wc = declared_float(keys::diffuse::k_wc);                    // 1/s
  float lifetime_min = declared_float(keys::diffuse::lifetime, 0);     // s
  float lifetime_max = declared_float(keys::diffuse::lifetime, 1);     // s
  // A fluid particle is a surface particle when |grad c| * h reaches this; below it its normal is
  // undefined and it contributes no crest potential (MODEL.md §8.10) ...
  float surface_threshold = declared_float(keys::diffuse::surface_threshold);
  // ... and has fewer neighbours within h than this fraction of a full neighbourhood (4/3 pi h^3 / V).
  // The gradient alone is not enough: in a disordered fluid its noise inside reaches half the value
  // at the surface, while the neighbour count drops by a quarter only in the outermost layer.
  float surface_neighbour_fraction = declared_float(keys::diffuse::surface_neighbour_fraction);

  // Classification (MODEL.md §3), on the fluid-neighbour count within h (scaled where walls are wet).
  float spray_below = declared_float(keys::diffuse::spray_below);
  float bubble_above = declared_float(keys::diffuse::bubble_above);
  float hysteresis = declared_float(keys::diffuse::hysteresis);
  bool count_solids = keys::diffuse::count_solids.value[0] != 0.0;

  // Advection (MODEL.md §4).
  Vec3f gravity = declared_vec3<Vec3f>(keys::scene::gravity);                      // m/s^2
  float buoyancy = declared_float(keys::diffuse::buoyancy);                        // k_b, multiples of -g
  float drag = declared_float(keys::diffuse::drag);                                // k_d per reference step
  float drag_reference_step = declared_float(keys::diffuse::drag_reference_step);  // s
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
