#pragma once
// The diffuse model's keys ("diffuse.*", MODEL.md §1-5, §8). Defaults are stated for r0 = 0.02 m water
// and carried to the scene's radius by Froude similarity (key_spec.h), so the same scene built at
// another scale emits alike; a key the user sets is taken literally, in SI units.
#include <array>

#include "sim/keys/key_spec.h"

namespace spume::keys::diffuse {

using enum KeyType;
using enum Scaling;
using enum Bound;

// Formation (MODEL.md §1). Trapped air from 2 m/s of approach summed over the neighbourhood, crests
// from the paper's curvature band, the kinetic clamp from 0.7 to 2.5 m/s of particle speed (0.5 m v^2
// with m = 0.064 kg). Rates: 300 samples/s at full potential, tuned on scenes/wave.json (1000 turned
// the whole surface white within a second, about 30 diffuse particles per fluid particle; 300 gives 3).
inline constexpr KeySpec tau_ta{.path = "diffuse.tau_ta", .type = Range, .unit = "m/s", .value = {2, 8},
                                .scaling = Velocity, .lo = 0, .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                .doc = "trapped-air clamp [min, max] on v_diff, Eq. 2"};
inline constexpr KeySpec tau_wc{.path = "diffuse.tau_wc", .type = Range, .value = {2, 8}, .lo = 0, .hi = 1e6,
                                .lo_bound = Closed, .hi_bound = Closed,
                                .doc = "wave-crest clamp [min, max] on the curvature sum, Eqs. 4-7"};
inline constexpr KeySpec tau_k{.path = "diffuse.tau_k", .type = Range, .unit = "J", .value = {0.0157, 0.2},
                               .scaling = Energy, .lo = 0, .hi = 1e12, .lo_bound = Closed, .hi_bound = Closed,
                               .default_text = "0.7 to 2.5 m/s at r0",
                               .doc = "kinetic-energy clamp [min, max] on 1/2 m v^2"};
// Eqs. 4-6 summed over this many support radii h: at h a cube's edge reaches about 0.6, never the
// paper's tau_wc,min = 2; at 2 h edges and corners reach about 4 and faces stay near 0, as the paper
// says Eq. 5 does (MODEL.md §8.10).
inline constexpr KeySpec crest_support{.path = "diffuse.crest_support", .value = {2}, .lo = 1, .hi = 2,
                                       .lo_bound = Closed, .hi_bound = Closed,
                                       .doc = "radius of the wave-crest sum (Eqs. 4-6), in multiples of h"};
inline constexpr KeySpec k_ta{.path = "diffuse.k_ta", .unit = "1/s", .value = {300}, .scaling = Rate, .lo = 0,
                              .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                              .doc = "samples per second from trapped air at full potential, Eq. 8"};
inline constexpr KeySpec k_wc{.path = "diffuse.k_wc", .unit = "1/s", .value = {300}, .scaling = Rate, .lo = 0,
                              .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                              .doc = "samples per second from wave crests at full potential, Eq. 8"};
inline constexpr KeySpec lifetime{.path = "diffuse.lifetime", .type = Range, .unit = "s", .value = {1.5, 4},
                                  .scaling = Time, .lo = 0, .hi = 1e6, .lo_bound = Open, .hi_bound = Closed,
                                  .doc = "[min, max] lifetime, set from the generation potential (MODEL.md §5)"};
inline constexpr KeySpec surface_threshold{
    .path = "diffuse.surface_threshold", .value = {0.3}, .lo = 0, .hi = 10, .lo_bound = Closed, .hi_bound = Closed,
    .doc = "a surface particle has |grad c| h at least this (MODEL.md §8.10)"};
inline constexpr KeySpec surface_neighbour_fraction{
    .path = "diffuse.surface_neighbour_fraction", .value = {0.75}, .lo = 0, .hi = 10, .lo_bound = Closed,
    .hi_bound = Closed, .doc = "... and fewer neighbours than this share of a full neighbourhood"};

// Classification (MODEL.md §3, §8.11).
inline constexpr KeySpec spray_below{.path = "diffuse.spray_below", .value = {6}, .lo = 0, .hi = 1e4,
                                     .lo_bound = Closed, .hi_bound = Closed,
                                     .doc = "fewer fluid neighbours than this: spray"};
inline constexpr KeySpec bubble_above{.path = "diffuse.bubble_above", .value = {20}, .lo = 0, .hi = 1e4,
                                      .lo_bound = Closed, .hi_bound = Closed,
                                      .doc = "more fluid neighbours than this: bubble (at least spray_below)"};
inline constexpr KeySpec hysteresis{.path = "diffuse.hysteresis", .value = {1}, .lo = 0, .hi = 100,
                                    .lo_bound = Closed, .hi_bound = Closed,
                                    .doc = "a particle changes type only past a limit by this many neighbours"};
inline constexpr KeySpec count_solids{
    .path = "diffuse.count_solids", .type = Boolean, .value = {1},
    .doc = "classification: a wet wall counts as the fluid it replaces, n / (1 - V_solid / V_h) over the union "
           "of solids (MODEL.md §8.11); the surface test sees the solids either way (§8.10)"};

// Advection (MODEL.md §4, §8.4-8.6).
inline constexpr KeySpec buoyancy{.path = "diffuse.buoyancy", .value = {2}, .lo = 0, .hi = 1e3, .lo_bound = Closed,
                                  .hi_bound = Closed, .doc = "k_b, bubble buoyancy in multiples of -g"};
inline constexpr KeySpec drag{.path = "diffuse.drag", .value = {0.5}, .lo = 0, .hi = 1e6, .lo_bound = Closed,
                              .hi_bound = Closed,
                              .doc = "k_d, share of the bubble's velocity gap closed per reference step "
                                     "(paper mode: at most 1)"};
inline constexpr KeySpec drag_reference_step{.path = "diffuse.drag_reference_step", .unit = "s", .value = {0.02},
                                             .scaling = Time, .lo = 0, .hi = 1e3, .lo_bound = Open,
                                             .hi_bound = Closed,
                                             .doc = "the step k_d refers to; exponential drag rate k_d / this"};
inline constexpr KeySpec bubble_drag{.path = "diffuse.bubble_drag", .type = Choice, .choices = "exponential|paper",
                                     .doc = "exponential: exact drag for any step; paper: the update as printed"};
inline constexpr KeySpec spray_integrator{.path = "diffuse.spray_integrator", .type = Choice,
                                          .choices = "exact|euler_cromer",
                                          .doc = "exact parabola, or Euler-Cromer as printed"};
inline constexpr KeySpec foam_velocity{.path = "diffuse.foam_velocity", .type = Choice, .choices = "fluid|stale",
                                       .doc = "foam carries the fluid's velocity, or keeps its own as printed"};
inline constexpr KeySpec substeps{.path = "diffuse.substeps", .type = Integer, .value = {1}, .lo = 1, .hi = 64,
                                  .lo_bound = Closed, .hi_bound = Closed, .doc = "diffuse steps per frame interval"};
inline constexpr KeySpec seed{.path = "diffuse.seed", .type = Integer, .value = {1}, .lo = 0, .hi = 9.2e18,
                              .lo_bound = Closed, .hi_bound = Closed,
                              .doc = "random seed (Philox keyed by seed, step, fluid id, sample)"};
inline constexpr KeySpec max_particles{.path = "diffuse.max_particles", .type = Integer, .lo = 0, .hi = 1099511627776.0,
                                       .lo_bound = Closed, .hi_bound = Closed, .default_text = "no limit",
                                       .doc = "emission budget: newborns thinned uniformly at random beyond it"};

inline constexpr auto all = std::to_array<const KeySpec*>(
    {&tau_ta, &tau_wc, &crest_support, &tau_k, &k_ta, &k_wc, &lifetime, &surface_threshold, &surface_neighbour_fraction, &spray_below,
     &bubble_above, &hysteresis, &count_solids, &buoyancy, &drag, &drag_reference_step, &bubble_drag,
     &spray_integrator, &foam_velocity, &substeps, &seed, &max_particles});

}  // namespace spume::keys::diffuse
