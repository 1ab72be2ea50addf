#include "sim/fluid/boundary.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume::fluid {

namespace {

struct Lattice {
  int n[3];
  float step[3];
  Vec3f lo;
  Vec3f at(int i, int j, int k) const {
    return Vec3f(lo[0] + (float(i) + 0.5f) * step[0], lo[1] + (float(j) + 0.5f) * step[1],
                 lo[2] + (float(k) + 0.5f) * step[2]);
  }
  float cell_volume() const { return step[0] * step[1] * step[2]; }
};

Lattice fit_lattice(const Vec3f& lo, const Vec3f& hi, float spacing) {
  Lattice l;
  l.lo = lo;
  for (int a = 0; a < 3; ++a) {
    const float extent = hi[a] - lo[a];
    l.n[a] = std::max(1, int(std::lround(extent / spacing)));
    l.step[a] = extent > 0.0f ? extent / float(l.n[a]) : spacing;
  }
  return l;
}

}  // namespace

void sample_tank_walls(const Vec3f& lo, const Vec3f& hi, float spacing, int layers, int open_axis,
                       std::vector<Vec3f>& out, float& cell_volume) {
  const Lattice l = fit_lattice(lo, hi, spacing);
  cell_volume = l.cell_volume();
  int first[3], last[3];  // inclusive index range of the padded lattice
  for (int a = 0; a < 3; ++a) {
    first[a] = -layers;
    last[a] = a == open_axis ? l.n[a] - 1 : l.n[a] - 1 + layers;  // nothing above an open top
  }
  auto interior = [&](int a, int i) { return i >= 0 && i < l.n[a]; };
  for (int k = first[2]; k <= last[2]; ++k)
    for (int j = first[1]; j <= last[1]; ++j) {
      if (!interior(1, j) || !interior(2, k)) {
        for (int i = first[0]; i <= last[0]; ++i) out.push_back(l.at(i, j, k));
      } else {  // the row crosses the free space: only its ends are wall
        for (int i = first[0]; i < 0; ++i) out.push_back(l.at(i, j, k));
        for (int i = l.n[0]; i <= last[0]; ++i) out.push_back(l.at(i, j, k));
      }
    }
}

void sample_box_layers(const Vec3f& lo, const Vec3f& hi, float spacing, int layers, std::vector<Vec3f>& out,
                       float& cell_volume) {
  const Lattice l = fit_lattice(lo, hi, spacing);
  cell_volume = l.cell_volume();
  auto shell = [&](int a, int i) { return i < layers || i >= l.n[a] - layers; };
  for (int k = 0; k < l.n[2]; ++k)
    for (int j = 0; j < l.n[1]; ++j) {
      if (shell(1, j) || shell(2, k)) {
        for (int i = 0; i < l.n[0]; ++i) out.push_back(l.at(i, j, k));
      } else {
        for (int i = 0; i < l.n[0]; ++i)
          if (shell(0, i)) out.push_back(l.at(i, j, k));
      }
    }
}

void sample_sphere_layers(const Vec3f& c, float radius, float spacing, int layers, std::vector<Vec3f>& out,
                          std::vector<float>& volume) {
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));  // golden angle, rad
  for (int layer = 0; layer < layers; ++layer) {
    const double outer = double(radius) - double(layer) * spacing;
    if (outer <= 0.0) break;
    const double inner = std::max(0.0, outer - spacing);
    const double r = 0.5 * (outer + inner);  // the shell's mid radius
    const long count = std::max(1L, std::lround(4.0 * std::numbers::pi * r * r / (double(spacing) * spacing)));
    const double shell_volume = 4.0 / 3.0 * std::numbers::pi * (outer * outer * outer - inner * inner * inner);
    for (long i = 0; i < count; ++i) {
      const double y = 1.0 - (2.0 * double(i) + 1.0) / double(count);
      const double ring = std::sqrt(std::max(0.0, 1.0 - y * y));
      const double phi = golden * double(i);
      out.push_back(c + (r * Vec3d(ring * std::cos(phi), y, ring * std::sin(phi))).cast<float>());
      volume.push_back(float(shell_volume / double(count)));
    }
  }
}

namespace {

// Layers whose centre (k + 1/2) spacing lies within h of the surface.
int layer_count(float spacing, float h) { return std::max(1, int(std::ceil(h / spacing - 0.5f - 1e-4f))); }

// Lattice cells along one axis, as fit_lattice rounds them, in double so that absurd solids are counted.
double cells_along(float extent, float spacing) { return std::max(1.0, double(std::round(extent / spacing))); }

double sphere_shell_count(float radius, float spacing, int layers) {
  double count = 0.0;
  for (int layer = 0; layer < layers; ++layer) {
    const double outer = double(radius) - double(layer) * spacing;
    if (outer <= 0.0) break;
    const double r = 0.5 * (outer + std::max(0.0, outer - spacing));
    count += std::max(1.0, std::round(4.0 * std::numbers::pi * r * r / (double(spacing) * spacing)));
  }
  return count;
}

}  // namespace

double count_boundary(const SolidSet& solids, float spacing, float h) {
  const int layers = layer_count(spacing, h);
  double total = 0.0;
  for (const Solid& s : solids.solids()) {
    if (s.kind == Solid::Kind::Sphere) {
      total += sphere_shell_count(s.radius, spacing, layers);
      continue;
    }
    double all = 1.0, inner = 1.0;
    for (int a = 0; a < 3; ++a) {
      const double n = cells_along(s.max[a] - s.min[a], spacing);
      if (s.kind == Solid::Kind::Tank) {
        const bool open = s.open_top && a == s.up_axis;
        all *= n + (open ? 1 : 2) * layers;  // the padded lattice around the free space
        inner *= n;
      } else {
        all *= n;
        inner *= std::max(0.0, n - 2.0 * layers);  // the core left out of a box's shell
      }
    }
    total += all - inner;
  }
  return total;
}

Boundary sample_boundary(const SolidSet& solids, float spacing, float h) {
  Boundary b;
  const int layers = layer_count(spacing, h);
  const auto& list = solids.solids();
  for (size_t s = 0; s < list.size(); ++s) {
    const Solid& solid = list[s];
    std::vector<Vec3f> points;
    std::vector<float> volume;
    float cell = 0.0f;
    switch (solid.kind) {
      case Solid::Kind::Tank:
        if (!(solid.min.array() < solid.max.array()).all()) fail("solid ", s, ": tank min must be below max");
        sample_tank_walls(solid.min, solid.max, spacing, layers, solid.open_top ? solid.up_axis : -1, points, cell);
        volume.assign(points.size(), cell);
        break;
      case Solid::Kind::Box:
        if (!(solid.min.array() < solid.max.array()).all()) fail("solid ", s, ": box min must be below max");
        sample_box_layers(solid.min, solid.max, spacing, layers, points, cell);
        volume.assign(points.size(), cell);
        if (solid.rotated() && !solid.dynamics.enabled) {
          const Vec3f c = solid.centre();
          for (Vec3f& x : points) x = c + solid.orientation * (x - c);
        }
        break;
      case Solid::Kind::Sphere:
        if (!(solid.radius > 0.0f)) fail("solid ", s, ": sphere radius must be > 0");
        sample_sphere_layers(solid.center, solid.radius, spacing, layers, points, volume);
        break;
    }
    if (solid.dynamics.enabled) {  // body frame: relative to the centre, unrotated
      const Vec3f c = solid.centre();
      for (Vec3f& x : points) x -= c;
    }
    if (points.size() + b.rest.size() >= size_t(UINT32_MAX) / 2) fail("solids: too many boundary particles");
    b.rest.insert(b.rest.end(), points.begin(), points.end());
    b.volume.insert(b.volume.end(), volume.begin(), volume.end());
    b.solid.insert(b.solid.end(), points.size(), uint32_t(s));
  }
  b.any_moving = solids.any_moving();
  b.h = h;
  return b;
}

void place_boundary(Boundary& b, const std::vector<SolidPlacement>& placements, bool first) {
  if (!first && !b.any_moving) return;  // static walls: grid, volumes and zero velocities stay
  const size_t n = b.size();
  std::vector<Vec3f> positions(n);
  parallel_for(n, 4096, [&](size_t lo, size_t hi) {
    for (size_t i = lo; i < hi; ++i) {
      const SolidPlacement& s = placements[b.solid[i]];
      positions[i] = s.body ? Vec3f(s.rotation * b.rest[i] + s.translation) : Vec3f(b.rest[i] + s.translation);
    }
  });
  b.grid.build(positions, b.h);
  std::span<const uint32_t> order = b.grid.sorted_to_original();
  b.sorted_volume.resize(n);
  b.sorted_solid.resize(n);
  b.sorted_on_body.resize(n);
  for (size_t k = 0; k < n; ++k) {
    b.sorted_volume[k] = b.volume[order[k]];
    b.sorted_solid[k] = b.solid[order[k]];
    b.sorted_on_body[k] = placements[b.sorted_solid[k]].body ? 1 : 0;
  }
  set_boundary_velocity(b, placements);
}

void set_boundary_velocity(Boundary& b, const std::vector<SolidPlacement>& placements) {
  const size_t n = b.size();
  b.sorted_velocity.resize(n);
  std::span<const Vec3f> x = b.grid.sorted_points();
  parallel_for(n, 4096, [&](size_t lo, size_t hi) {
    for (size_t k = lo; k < hi; ++k) {
      const SolidPlacement& s = placements[b.sorted_solid[k]];
      b.sorted_velocity[k] = s.body ? Vec3f(s.velocity + s.angular_velocity.cross(x[k] - s.translation)) : s.velocity;
    }
  });
}

}  // namespace spume::fluid
