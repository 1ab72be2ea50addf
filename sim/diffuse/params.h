#pragma once
// Every parameter of the diffuse model, in SI units, as plain typed values. The scene reader
// (scene/diffuse_params_reader.cpp) fills and validates it; defaults live there, in one place.
#include <cstdint>
#include <optional>

#include "core/vec.h"

namespace spume {

struct ClampRange {
  float lo = 0.0f, hi = 1.0f;  // lo < hi always (validated)
};

enum class BubbleDrag { Paper, Exponential };       // MODEL.md §4 as printed | §8.4 exact integration
enum class SprayIntegrator { EulerCromer, Exact };  // MODEL.md §4 as printed | §8.6 exact ballistic
enum class FoamVelocity { Stale, Fluid };           // MODEL.md §4 as printed | §8.5 foam carries the fluid's

struct DiffuseParams {
  // Formation (MODEL.md §1).
  ClampRange trapped_air;   // tau_ta, on v_diff in m/s
  ClampRange wave_crest;    // tau_wc, on the dimensionless curvature sum
  ClampRange kinetic;       // tau_k, on E_k in J
  float k_ta = 0.0f;        // max samples per second from trapped air
  float k_wc = 0.0f;        // max samples per second from wave crests
  float lifetime_min = 0.0f, lifetime_max = 0.0f;  // s
  // A fluid particle is a surface particle when |grad c| * h reaches this; below it its normal is
  // undefined and it contributes no crest potential (MODEL.md §8.10).
  float surface_threshold = 0.3f;
  // ... and has fewer neighbours within h than this fraction of a full neighbourhood (4/3 pi h^3 / V).
  // The gradient alone is not enough: in a disordered fluid its noise inside reaches half the value
  // at the surface, while the neighbour count drops by a quarter only in the outermost layer.
  float surface_neighbour_fraction = 0.75f;

  // Classification (MODEL.md §3), on the fluid-neighbour count within h (plus the solids' share).
  float spray_below = 6.0f;    // fewer neighbours -> spray
  float bubble_above = 20.0f;  // more neighbours -> bubble
  float hysteresis = 1.0f;     // a particle changes type only when the count passes a limit by this much
  bool count_solids = true;    // MODEL.md §8.11

  // Advection (MODEL.md §4).
  Vec3f gravity = Vec3f(0.0f, -9.81f, 0.0f);  // m/s^2
  float buoyancy = 2.0f;                      // k_b, multiples of -g
  float drag = 0.5f;                          // k_d: fraction of the velocity gap per reference step
  float drag_reference_step = 0.02f;          // s; the exponential mode's rate is k_d / this step
  BubbleDrag bubble_drag = BubbleDrag::Exponential;
  SprayIntegrator spray_integrator = SprayIntegrator::Exact;
  FoamVelocity foam_velocity = FoamVelocity::Fluid;

  int substeps = 1;                          // diffuse steps per frame interval
  uint64_t seed = 1;
  std::optional<uint64_t> max_particles;     // emission budget
};

}  // namespace spume
