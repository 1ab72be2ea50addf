#include "sim/diffuse/advection.h"

#include <cmath>

namespace spume {

DiffuseType classify(float count, const DiffuseParams& p, const DiffuseType* previous) {
  auto raw = [&](float spray_below, float bubble_above) {
    if (count < spray_below) return DiffuseType::Spray;
    if (count > bubble_above) return DiffuseType::Bubble;
    return DiffuseType::Foam;
  };
  if (!previous) return raw(p.spray_below, p.bubble_above);
  // Widen the band of the current type by the hysteresis on the sides it borders.
  switch (*previous) {
    case DiffuseType::Spray: return raw(p.spray_below + p.hysteresis, p.bubble_above);
    case DiffuseType::Foam: return raw(p.spray_below - p.hysteresis, p.bubble_above + p.hysteresis);
    case DiffuseType::Bubble: return raw(p.spray_below, p.bubble_above - p.hysteresis);
  }
  return raw(p.spray_below, p.bubble_above);
}

void advance_spray(Vec3f& x, Vec3f& v, const Vec3f& g, float dt, SprayIntegrator integrator) {
  if (integrator == SprayIntegrator::EulerCromer) {
    v += dt * g;
    x += dt * v;
  } else {
    x += dt * v + (0.5f * dt * dt) * g;
    v += dt * g;
  }
}

void advance_foam(Vec3f& x, Vec3f& v, const Vec3f& u, float dt, FoamVelocity mode) {
  x += dt * u;
  if (mode == FoamVelocity::Fluid) v = u;
}

BubbleStep bubble_step(const DiffuseParams& p, float dt) {
  BubbleStep s;
  s.mode = p.bubble_drag, s.dt = dt, s.drag = p.drag;
  s.lift = -p.buoyancy * p.gravity;  // acceleration opposite gravity
  if (p.bubble_drag == BubbleDrag::Exponential && p.drag > 0.0f) {
    const double tau = double(p.drag_reference_step) / double(p.drag);
    s.tau = float(tau);
    s.decay = float(std::exp(-double(dt) / tau));
    s.settle = float(-std::expm1(-double(dt) / tau) * tau);  // tau (1 - e^{-dt/tau}), exact for tiny tau
  }
  return s;
}

void advance_bubble(Vec3f& x, Vec3f& v, const Vec3f& u, const DiffuseParams& p, float dt) {
  advance_bubble(x, v, u, bubble_step(p, dt));
}

void advance_bubble(Vec3f& x, Vec3f& v, const Vec3f& u, const BubbleStep& s) {
  const float dt = s.dt;
  if (s.mode == BubbleDrag::Paper) {
    v += dt * s.lift + s.drag * (u - v);
    x += dt * v;
    return;
  }
  if (s.drag <= 0.0f) {  // no drag: free rise, exactly
    x += dt * v + (0.5f * dt * dt) * s.lift;
    v += dt * s.lift;
    return;
  }
  // v(t) = w + (v0 - w) e^{-t/tau} with terminal w = u + tau lift; x follows by integrating v.
  const Vec3f terminal = u + s.tau * s.lift;
  const Vec3f gap = v - terminal;
  x += dt * terminal + s.settle * gap;
  v = terminal + s.decay * gap;
}

}  // namespace spume
