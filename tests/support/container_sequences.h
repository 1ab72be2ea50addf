#pragma once
// Fluid sequences built by hand for the container inference, with the walls known by construction:
// lattices of spacing 2r whose outermost centres lie r inside the walls they touch (as SPlisHSPlasH
// keeps them), one list of positions per frame (an empty list is an empty frame).
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/vec.h"
#include "sim/io/bgeo.h"

namespace spume::testing {

constexpr float kSeqRadius = 0.01f;  // r of every sequence here (spacing 0.02 m)

// Lattice cells [0, nx) x [0, ny) x [0, nz) of spacing 2r, the first centre at origin + (r, r, r).
inline std::vector<Vec3f> cells(const Vec3f& origin, int nx, int ny, int nz) {
  std::vector<Vec3f> p;
  const float s = 2.0f * kSeqRadius;
  for (int l = 0; l < nz; ++l)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) p.push_back(origin + Vec3f(kSeqRadius + s * float(i), kSeqRadius + s * float(j),
                                                                kSeqRadius + s * float(l)));
  return p;
}

// A column collapsing in the open-top tank [0, 0.6] x [0, 1] x [0, 0.1] (shifted by `origin`), 16
// frames: it stands against the -x wall, on the floor, between the z walls from the first frame on;
// its front runs along +x (3 cells a frame) and reaches the +x wall in its 8th frame, where it stays while
// the column keeps sinking. Walls: -x, +x, -y, -z, +z; +y open.
inline std::vector<std::vector<Vec3f>> collapsing_column(const Vec3f& origin = Vec3f::Zero()) {
  std::vector<std::vector<Vec3f>> frames;
  for (int k = 0; k < 16; ++k) frames.push_back(cells(origin, std::min(10 + 3 * k, 30), std::max(20 - k, 5), 5));
  return frames;
}
inline const Vec3f kColumnTankMin(0.0f, 0.0f, 0.0f), kColumnTankMax(0.6f, 1.0f, 0.1f);

// An 8 x 8 x 8 block of spacing 2r falling freely from rest under g = 9.81 m/s^2 along -y, 21 frames
// at 25 fps (it falls 1.96 m): it touches nothing.
inline std::vector<std::vector<Vec3f>> falling_block() {
  std::vector<std::vector<Vec3f>> frames;
  for (int k = 0; k < 21; ++k) {
    const float t = float(k) / 25.0f;
    frames.push_back(cells(Vec3f(0.0f, 4.0f - 0.5f * 9.81f * t * t, 0.0f), 8, 8, 8));
  }
  return frames;
}

// A column in the tank [0, 0.6] x [0, 1] x [0, 0.1] whose -x side follows a piston, 20 frames: still
// for 4 frames at x = 0.08, then oscillating 4 cells either way; the column sinks a cell every 2
// frames. Walls: +x, -y, -z, +z; -x (the piston) and +y open.
inline std::vector<std::vector<Vec3f>> column_at_a_piston() {
  std::vector<std::vector<Vec3f>> frames;
  for (int k = 0; k < 20; ++k) {
    const int shift = k < 4 ? 0 : int(std::lround(4.0 * std::sin(0.8 * (k - 4))));
    frames.push_back(cells(Vec3f(0.02f * float(shift) + 0.08f, 0, 0), 26 - shift, 20 - k / 2, 5));
  }
  return frames;
}

// Frame `first + k` of `frames` as gzipped BGEO files `dir/fluid_<n>.bgeo`, with ids (lattice order)
// and velocities: the difference to the next frame where it holds as many particles, else zero.
// Returns the pattern.
inline std::string write_sequence(const std::filesystem::path& dir, const std::vector<std::vector<Vec3f>>& frames,
                                  double fps = 25.0, int first = 1) {
  std::filesystem::create_directories(dir);
  for (size_t k = 0; k < frames.size(); ++k) {
    FluidFrame f;
    f.index = first + int(k);
    f.time = double(f.index) / fps;
    f.positions = frames[k];
    const std::vector<Vec3f>& next = frames[std::min(k + 1, frames.size() - 1)];
    for (size_t i = 0; i < frames[k].size(); ++i) {
      f.ids.push_back(uint32_t(i));
      const bool paired = k + 1 < frames.size() && next.size() == frames[k].size();
      f.velocities.push_back(paired ? Vec3f((next[i] - frames[k][i]) * float(fps)) : Vec3f::Zero());
    }
    write_bgeo(dir / ("fluid_" + std::to_string(f.index) + ".bgeo"), f);
  }
  return (dir / "fluid_%d.bgeo").string();
}

}  // namespace spume::testing
