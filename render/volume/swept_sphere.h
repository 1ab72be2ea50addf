#pragma once
// A diffuse sphere moving during the shutter, seen along one eye ray (motion blur, MODEL.md §13).
// Its path is cut into linear pieces (one for foam and bubbles, kSprayPieces along the parabola for
// spray, which flies ballistically); a piece moves its centre from a to a + b while the shutter time
// runs over [t0, t0 + w] (fractions of the shutter, the pieces of one particle tiling [0, 1]).
//
// Along the ray x(s) = o + s d (|d| = 1), the piece covers the points of the (s, tau) plane inside
// an ellipse, tau in [0, 1] its local time: |o + s d - a - tau b|^2 < r^2. Its time-averaged chord,
// the area of that ellipse over tau in [0, 1] times w, is closed form: w * int_0^1 2 h(tau) dtau, h
// the half chord, an integral of the form int sqrt(R^2 - u^2) du (ellipse_area below).
#include <array>
#include <cstdint>

#include "sim/core/frames.h"
#include "sim/core/vec.h"

namespace spume {

inline constexpr int kSprayPieces = 4;

struct PathPiece {
  Vec3d a, b;          // m; centre at the piece's start and its displacement over the piece
  double t0 = 0, w = 1;  // its share of the shutter: [t0, t0 + w] in [0, 1]
};

// The pieces of a particle at `centre` with `velocity` at the frame's time, over the shutter
// [open, close] (s, relative to the frame's time). Spray falls under `gravity` (m/s^2); the other
// types move in a straight line. Returns the number of pieces written.
int path_pieces(const Vec3d& centre, const Vec3d& velocity, DiffuseType type, double open, double close, const Vec3d& gravity,
                std::array<PathPiece, kSprayPieces>& out);

// Most a spray path between its piece ends strays from the straight pieces, m: g T^2 / (8 n^2) for a
// shutter T cut into n pieces. Added to the radius wherever the path is bounded.
double path_sag(double open, double close, const Vec3d& gravity);

// One piece seen along one ray: where along it (s in [s_lo, s_hi], exactly the points the sphere
// covers at some time of the piece) and how much (area: its chord length averaged over the shutter).
struct SweptChord {
  double s_lo = 0, s_hi = 0;  // m along the ray
  double area = 0;            // m: int over the piece's share of the shutter of the chord length
  uint32_t type = 0, particle = 0;
};

// A piece as seen from the eye, worked out once for all the rays of its rectangle.
struct EyePiece {
  Vec3d a, b, mid;        // start and middle relative to the eye, displacement
  double r2 = 0, bound2 = 0;  // radius^2; the squared radius of the sphere around the whole piece
  double w = 1;
  double aa = 0, ab = 0, bb = 0, mid2 = 0;  // |a|^2, a.b, |b|^2, |mid|^2
};
EyePiece eye_piece(const PathPiece& piece, double r2, const Vec3d& origin);

// The piece against the ray from the eye along unit `d`; false when it never touches the ray.
bool swept_chord(const EyePiece& piece, const Vec3d& d, SweptChord& out);
inline bool swept_chord(const PathPiece& piece, double r2, const Vec3d& origin, const Vec3d& d, SweptChord& out) {
  return swept_chord(eye_piece(piece, r2, origin), d, out);
}

// int_{u0}^{u1} 2 sqrt(R^2 - u^2) du for -R <= u0 <= u1 <= R.
double ellipse_area(double R, double u0, double u1);

}  // namespace spume
