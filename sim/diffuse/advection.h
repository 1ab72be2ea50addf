#pragma once
// Classification (MODEL.md §3) and per-type advection (§4) of single diffuse particles: pure
// functions, so each is testable against its closed form.
#include "sim/core/frames.h"
#include "sim/diffuse/params.h"

namespace spume {

// Type from the neighbour count: < spray_below -> spray, > bubble_above -> bubble, else foam. A
// particle that already has a type keeps it unless the count passes the limit by the hysteresis.
DiffuseType classify(float neighbour_count, const DiffuseParams& params, const DiffuseType* previous);

// Spray under gravity over dt (Euler-Cromer as printed, or the exact parabola).
void advance_spray(Vec3f& x, Vec3f& v, const Vec3f& gravity, float dt, SprayIntegrator integrator);

// Foam moves with the fluid; its velocity becomes the fluid's (or stays as it was: Stale).
void advance_foam(Vec3f& x, Vec3f& v, const Vec3f& fluid_velocity, float dt, FoamVelocity mode);

// Bubble: buoyancy -k_b g and drag towards the fluid velocity. Paper: v += dt(-k_b g) + k_d (u - v),
// x += dt v. Exponential: dv/dt = -k_b g + (u - v)/tau with tau = reference_step / k_d, integrated
// exactly over dt (stable for any k_d; equals the paper's terminal speed at dt = reference_step).
void advance_bubble(Vec3f& x, Vec3f& v, const Vec3f& fluid_velocity, const DiffuseParams& params, float dt);

// The part of a bubble step that depends only on the parameters and dt (two exponentials), worked
// out once per step instead of once per bubble; advance_bubble above is bubble_step + this overload.
struct BubbleStep {
  BubbleDrag mode = BubbleDrag::Exponential;
  float dt = 0.0f, drag = 0.0f;
  Vec3f lift = Vec3f::Zero();          // -k_b g
  float tau = 0.0f, decay = 0.0f, settle = 0.0f;  // exponential mode with drag > 0
};
BubbleStep bubble_step(const DiffuseParams& params, float dt);
void advance_bubble(Vec3f& x, Vec3f& v, const Vec3f& fluid_velocity, const BubbleStep& step);

}  // namespace spume
