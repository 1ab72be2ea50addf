#include "render/volume/swept_sphere.h"

#include <algorithm>
#include <cmath>

namespace spume {

int path_pieces(const Vec3d& centre, const Vec3d& velocity, DiffuseType type, double open, double close, const Vec3d& gravity,
                std::array<PathPiece, kSprayPieces>& out) {
  const double span = close - open;
  if (type != DiffuseType::Spray) {
    out[0] = {centre + open * velocity, span * velocity, 0.0, 1.0};
    return 1;
  }
  auto at = [&](double t) -> Vec3d { return centre + t * velocity + (0.5 * t * t) * gravity; };
  for (int k = 0; k < kSprayPieces; ++k) {
    const double ta = open + span * k / kSprayPieces, tb = open + span * (k + 1) / kSprayPieces;
    out[size_t(k)] = {at(ta), at(tb) - at(ta), double(k) / kSprayPieces, 1.0 / kSprayPieces};
  }
  return kSprayPieces;
}

double path_sag(double open, double close, const Vec3d& gravity) {
  const double piece = (close - open) / kSprayPieces;
  return gravity.norm() * piece * piece / 8.0;
}

double ellipse_area(double R, double u0, double u1) {
  if (!(R > 0.0) || !(u1 > u0)) return 0.0;
  auto F = [R](double u) {
    const double x = std::clamp(u / R, -1.0, 1.0);
    return R * R * (x * std::sqrt(std::max(0.0, 1.0 - x * x)) + std::asin(x));
  };
  return F(u1) - F(u0);
}

EyePiece eye_piece(const PathPiece& piece, double r2, const Vec3d& origin) {
  EyePiece e;
  e.a = piece.a - origin, e.b = piece.b, e.mid = e.a + 0.5 * piece.b;
  const double bound = std::sqrt(r2) + 0.5 * piece.b.norm();
  e.r2 = r2, e.bound2 = bound * bound, e.w = piece.w;
  e.aa = e.a.squaredNorm(), e.ab = e.a.dot(e.b), e.bb = e.b.squaredNorm(), e.mid2 = e.mid.squaredNorm();
  return e;
}

bool swept_chord(const EyePiece& piece, const Vec3d& d, SweptChord& out) {
  // Most rays of a streak's rectangle miss a piece: first the sphere around it.
  const double along = piece.mid.dot(d);
  if (piece.mid2 - along * along >= piece.bound2) return false;
  const double r2 = piece.r2;
  // Along the ray and across it (squared lengths and products of the parts across, from the piece's
  // own, as the still integrator's |oc|^2 - tc^2).
  const double tca = piece.a.dot(d), tcb = piece.b.dot(d);
  const double C = piece.aa - tca * tca, Bq = piece.ab - tca * tcb, A = std::max(0.0, piece.bb - tcb * tcb);
  // The nearest the centre comes to the ray during the piece.
  const double tau = A > 0.0 ? std::clamp(-Bq / A, 0.0, 1.0) : 0.0;
  if (C + tau * (2.0 * Bq + A * tau) >= r2) return false;
  double area;
  if (A <= 1e-12 * r2) {  // (almost) no motion across the ray: the chord is constant
    const double h = std::sqrt(std::max(0.0, r2 - (C + Bq + 0.25 * A)));
    area = 2.0 * h;
    out.s_lo = std::min(tca, tca + tcb) - h, out.s_hi = std::max(tca, tca + tcb) + h;
  } else {
    // b^2(tau) = A (tau - tm)^2 + b_min^2; with u = sqrt(A) (tau - tm) the chord is 2 sqrt(R^2 - u^2).
    const double tm = -Bq / A, R2 = r2 - (C - Bq * Bq / A);
    if (!(R2 > 0.0)) return false;
    const double R = std::sqrt(R2), sa = std::sqrt(A);
    area = ellipse_area(R, std::max(-R, -sa * tm), std::min(R, sa * (1.0 - tm))) / sa;
    // The support's ends: tc(tau) +- h(tau) is concave (convex), so its extreme over the times the
    // sphere meets the ray is its stationary point u = +-R tcb / sqrt(A + tcb^2), clamped.
    const double lo = std::max(0.0, tm - R / sa), hi = std::min(1.0, tm + R / sa);
    const double ut = R * tcb / std::sqrt(A + tcb * tcb) / sa;
    auto half = [&](double t) { return std::sqrt(std::max(0.0, R2 - A * (t - tm) * (t - tm))); };
    const double t_hi = std::clamp(tm + ut, lo, hi), t_lo = std::clamp(tm - ut, lo, hi);
    out.s_hi = tca + tcb * t_hi + half(t_hi), out.s_lo = tca + tcb * t_lo - half(t_lo);
  }
  out.area = piece.w * area;
  return out.area > 0.0 && out.s_hi > out.s_lo;
}

}  // namespace spume
