// Study 4: surface reconstruction, marching-cubes cell size and mesh smoothing against run time and
// against the distance of the mesh vertices to an analytic surface, and the angle of their normals to
// its normal: a ball of particles (the sphere of the same volume, N (2r)^3) and a box of particles (the
// box the lattice cells tile).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "render/surface/reconstruct.h"
#include "render/app/report/study.h"

namespace spume::report {
namespace {

constexpr float kR = 0.01f;  // particle radius, m (the results are in units of r)

struct Shape {
  std::string name;
  std::vector<Vec3f> particles;
  std::function<double(const Vec3f&)> distance;  // signed, m: > 0 outside the analytic surface
};

// The analytic surface's unit normal near x: the gradient of the signed distance (central differences;
// off the box's edges and corners it is the normal of the nearest face, around them the rounded one).
Vec3d analytic_normal(const Shape& shape, const Vec3f& x) {
  const float e = 1e-3f * kR;
  Vec3d g;
  for (int a = 0; a < 3; ++a) {
    Vec3f lo = x, hi = x;
    lo[a] -= e, hi[a] += e;
    g[a] = shape.distance(hi) - shape.distance(lo);
  }
  return g.normalized();
}

Shape particle_ball(float radius_in_r) {
  Shape s{"ball", {}, {}};
  const float spacing = 2 * kR, radius = radius_in_r * kR;
  const int n = int(radius / spacing) + 1;
  for (int k = -n; k <= n; ++k)
    for (int j = -n; j <= n; ++j)
      for (int i = -n; i <= n; ++i)
        if (const Vec3f x = spacing * Vec3f(float(i), float(j), float(k)); x.norm() <= radius) s.particles.push_back(x);
  // The sphere holding the particles' volume: each particle stands for a (2r)^3 cell.
  const double equivalent = spacing * std::cbrt(3.0 * double(s.particles.size()) / (4.0 * std::numbers::pi));
  s.name = str("ball of ", s.particles.size(), " particles (sphere R = ", num(equivalent / kR, 3), " r)");
  s.distance = [equivalent](const Vec3f& x) { return double(x.norm()) - equivalent; };
  return s;
}

Shape particle_box(int n) {
  Shape s{str("box of ", n, "^3 particles (side ", 2 * n, " r)"), {}, {}};
  const float spacing = 2 * kR, side = float(n) * spacing;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) s.particles.push_back(spacing * Vec3f(i + 0.5f, j + 0.5f, k + 0.5f));
  s.distance = [side](const Vec3f& x) {
    // Signed distance to the box [0, side]^3.
    const Vec3d q = (x.cast<double>() - Vec3d::Constant(side / 2.0)).cwiseAbs() - Vec3d::Constant(side / 2.0);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  return s;
}

struct Measure {
  double ms = 0, mean = 0, rms = 0, max = 0, bias = 0;  // distances in units of r
  double normal_mean = 0, normal_median = 0, normal_max = 0;  // degrees between mesh and analytic normals
  size_t vertices = 0, triangles = 0;
};

Measure measure(const Shape& shape, float cell, int smoothing, int repeats) {
  SurfaceParams p;
  p.particle_radius = kR;
  p.cell_factor = cell;
  p.smoothing = smoothing;
  Measure m;
  std::vector<double> times;
  TriangleMesh mesh;
  for (int k = 0; k < repeats; ++k) {
    const Stopwatch t0;
    mesh = reconstruct_surface(shape.particles, p);
    times.push_back(t0.milliseconds());
  }
  std::sort(times.begin(), times.end());
  m.ms = times[times.size() / 2];
  m.vertices = mesh.vertices.size();
  m.triangles = mesh.triangle_count();
  if (m.vertices == 0) fail("surface study: the ", shape.name, " gave an empty mesh at cell ", cell, " r");
  std::vector<double> angles;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3f& v = mesh.vertices[i];
    const double d = shape.distance(v) / kR;
    m.mean += std::abs(d), m.rms += d * d, m.bias += d, m.max = std::max(m.max, std::abs(d));
    const double c = std::clamp(mesh.normals[i].cast<double>().dot(analytic_normal(shape, v)), -1.0, 1.0);
    const double angle = std::acos(c) * 180.0 / std::numbers::pi;
    m.normal_mean += angle, m.normal_max = std::max(m.normal_max, angle);
    angles.push_back(angle);
  }
  // The median: the faces' and the sphere's bulk, where the lattice's ripple shows, not the few
  // vertices at the box's rounded edges.
  std::nth_element(angles.begin(), angles.begin() + ptrdiff_t(angles.size() / 2), angles.end());
  m.normal_median = angles[angles.size() / 2];
  m.mean /= double(m.vertices), m.bias /= double(m.vertices), m.rms = std::sqrt(m.rms / double(m.vertices));
  m.normal_mean /= double(m.vertices);
  return m;
}

}  // namespace

StudyResult study_surface(const StudyContext& c) {
  StudyResult r;
  r.key = "surface";
  r.title = "4. Surface reconstruction: cell size and smoothing against distance to the analytic surface and run time";
  const int smoothing_default = SurfaceParams{}.smoothing;
  r.measures = str(
      "Marching-cubes cell (render.surface_cell, in units of the particle radius r) at the default smoothing (",
      smoothing_default, " iterations), then Taubin smoothing (render.surface_smoothing, iterations) at the default cell ",
      "1 r, are varied on a ball and a box of particles on the fluid's lattice (spacing 2r, kernel support h = 4r); every "
      "mesh vertex is measured against the analytic surface (the sphere of the particles' volume N (2r)^3, and the box "
      "the lattice cells tile): its distance, and the angle between its normal and the surface's. Run time is the "
      "median of 3 reconstructions");
  const std::vector<float> cells = c.quick ? std::vector<float>{2.0f, 1.0f, 0.5f}
                                           : std::vector<float>{2.0f, 1.5f, 1.0f, 0.75f, 0.5f, 0.35f, 0.25f};
  const std::vector<int> smoothings = c.quick ? std::vector<int>{0, smoothing_default, 16}
                                              : std::vector<int>{0, 1, 2, smoothing_default, 8, 16};
  const std::vector<Shape> shapes = {particle_ball(c.quick ? 20.0f : 40.0f), particle_box(c.quick ? 24 : 40)};
  r.table.columns = {"shape", "particles", "cell_r", "smoothing", "vertices", "triangles", "ms", "mean_abs_distance_r",
                     "rms_distance_r", "max_abs_distance_r", "mean_signed_distance_r", "mean_normal_error_deg",
                     "median_normal_error_deg", "max_normal_error_deg"};
  Panel error{"Mesh vertices against the analytic surface", "marching-cubes cell (units of r)",
              "|vertex distance| to the analytic surface (units of r)", true, true, false, {}, 2};
  Panel time{"Reconstruction time", "marching-cubes cell (units of r)", "ms per reconstruction", true, true, false, {}, 2};
  Panel smooth{"Smoothing at cell 1 r", "Taubin iterations", "mean |distance| (r); median normal error (deg / 10)",
               false, false, false, {}, 10};
  std::string reading;
  // Does refining below the default still move the mean distance, by 30% and by more than 0.02 r?
  bool grid_matters = false;
  for (size_t s = 0; s < shapes.size(); ++s) {
    const Shape& shape = shapes[s];
    const std::string label = s == 0 ? "ball" : "box";
    auto row = [&](float cell, int smoothing, const Measure& m) {
      r.table.add_row({label, std::to_string(shape.particles.size()), num(cell), std::to_string(smoothing),
                       std::to_string(m.vertices), std::to_string(m.triangles), num(m.ms), num(m.mean), num(m.rms),
                       num(m.max), num(m.bias), num(m.normal_mean), num(m.normal_median),
                       num(m.normal_max)});
    };
    Series e{label + ", mean", {}, true}, e_max{label + ", max", {}, true}, t{label, {}, true};
    std::vector<Measure> ms;
    for (float cell : cells) {
      c.progress(str("surface: ", shape.name, ", cell ", cell, " r"));
      const Measure m = measure(shape, cell, smoothing_default, 3);
      ms.push_back(m);
      row(cell, smoothing_default, m);
      e.points.push_back({cell, m.mean}), e_max.points.push_back({cell, m.max}), t.points.push_back({cell, m.ms});
    }
    error.series.push_back(e), error.series.push_back(e_max), time.series.push_back(t);
    const auto at_default = std::find(cells.begin(), cells.end(), 1.0f) - cells.begin();
    const Measure& coarse = ms.front();
    const Measure& fine = ms.back();
    const Measure& def = ms[size_t(at_default)];
    grid_matters |= std::abs(fine.mean - def.mean) >= std::max(0.3 * def.mean, 0.02);
    reading += str("For the ", shape.name, ", the mean vertex distance goes from ", num(coarse.mean, 3), " r at cell ",
                   num(cells.front()), " r to ", num(def.mean, 3), " r at the default 1 r and ", num(fine.mean, 3),
                   " r at ", num(cells.back()), " r (max ", num(fine.max, 3), " r; mean signed ", num(fine.bias, 3),
                   " r, negative = inside), while the time grows from ", num(coarse.ms, 3), " ms to ", num(def.ms, 3),
                   " ms and ", num(fine.ms, 3), " ms (", num(fine.ms / def.ms, 3), "x the default). ");
    Series sd{label + ", distance", {}, true}, sn{label + ", median normal error / 10", {}, true, true};
    std::vector<Measure> by_smoothing;
    for (int k : smoothings) {
      c.progress(str("surface: ", shape.name, ", smoothing ", k));
      const Measure m = k == smoothing_default ? def : measure(shape, 1.0f, k, 3);
      by_smoothing.push_back(m);
      if (k != smoothing_default) row(1.0f, k, m);
      sd.points.push_back({double(k), m.mean}), sn.points.push_back({double(k), m.normal_median / 10.0});
    }
    smooth.series.push_back(sd), smooth.series.push_back(sn);
    const Measure& raw = by_smoothing.front();
    const Measure& most = by_smoothing.back();
    reading += str("Smoothing (", shape.name, ", cell 1 r): unsmoothed, the mean distance is ", num(raw.mean, 3),
                   " r and the normal error ", num(raw.normal_median, 3), " deg median, ", num(raw.normal_mean, 3),
                   " mean, ", num(raw.normal_max, 3), " max; at the default ", smoothing_default, " iterations ",
                   num(def.mean, 3), " r and ", num(def.normal_median, 3), " / ", num(def.normal_mean, 3), " / ",
                   num(def.normal_max, 3), " deg; at ", smoothings.back(), " iterations ", num(most.mean, 3), " r and ",
                   num(most.normal_median, 3), " / ", num(most.normal_mean, 3), " / ", num(most.normal_max, 3),
                   " deg. ");
  }
  reading += grid_matters
                 ? "Refining below 1 r still moves the mean distance (by 30% and more than 0.02 r) for at least one shape: the grid's "
                   "sampling of the colour field is part of the error there."
                 : "Below 1 r the grid stops mattering (the mean distance moves by less than 30% or less than 0.02 r): what remains is set "
                   "by the particles themselves (the lattice ball's steps, the kernel rounding the box's edges and "
                   "corners over h = 4r), not by the grid's sampling of the field.";
  r.reading = reading;
  r.figure.panels = {error, time, smooth};
  r.figure.columns = 3;
  return r;
}

}  // namespace spume::report
