// Study 1: rendering. Eq. 9 ray marching at dx = 2r, r, r/2, r/4, r/8 (r the smallest drawn diffuse
// radius) against the exact interval integration (the dx -> 0 limit, computed from the ray/sphere
// chords): transmittance L and the final 8-bit image, against the volume pass's time, on the busiest
// frame of the scene.
#include <algorithm>
#include <cmath>

#include "render/app/scene/scene_render.h"
#include "render/stage/render_stage.h"
#include "render/app/report/convergence_fit.h"
#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "render/image/image.h"
#include "render/frame/frame_renderer.h"
#include "render/app/report/report_scene.h"
#include "render/surface/reconstruct.h"
#include "render/volume/composite.h"
#include "render/volume/volume_pass.h"

namespace spume::report {
namespace {

struct Errors {
  double l_rms = 0, l_max = 0, rgb_rms = 0, rgb_max = 0;
};

Errors compare(const VolumeImage& march, const ImageRGB8& march8, const VolumeImage& exact, const ImageRGB8& exact8) {
  Errors e;
  for (size_t i = 0; i < exact.pixel_count(); ++i) {
    const double d = double(march.transmittance[i]) - double(exact.transmittance[i]);
    e.l_rms += d * d, e.l_max = std::max(e.l_max, std::abs(d));
  }
  e.l_rms = std::sqrt(e.l_rms / double(exact.pixel_count()));
  for (size_t i = 0; i < exact8.rgb.size(); ++i) {
    const double d = double(march8.rgb[i]) - double(exact8.rgb[i]);
    e.rgb_rms += d * d, e.rgb_max = std::max(e.rgb_max, std::abs(d));
  }
  e.rgb_rms = std::sqrt(e.rgb_rms / double(exact8.rgb.size()));
  return e;
}

}  // namespace

StudyResult study_render(const StudyContext& c) {
  StudyResult r;
  r.key = "render";
  r.title = "1. Rendering: Eq. 9 ray marching against the exact interval integration";
  SceneSetup setup = load_report_scene(c);
  if (c.quick) setup.render.width /= 2, setup.render.height /= 2;
  if (!setup.render.draws_diffuse()) fail(setup.sim.name, ": the scene draws no diffuse type; nothing to march");
  SceneRender scene_render_of_setup = scene_render(setup.sim, setup.out_root);
  PreparedRender prepared = prepare_render(scene_render_of_setup.scene, setup.render);
  const int frame = busiest_frame(setup);
  const LoadedFrame loaded = load_frame(prepared, frame);
  const RenderSettings& settings = prepared.settings;
  FrameRenderer renderer(settings);  // for the camera of this frame's time
  const Camera camera = renderer.camera_at_time(loaded.time);

  // The background C_b and the surfaces the rays stop at or dim behind, once: they are the same for
  // every integrator, so only the volume pass is timed.
  c.progress(str("render: frame ", frame, " of ", setup.sim.name, ", ", loaded.diffuse.size(),
                 " diffuse particles, background"));
  TriangleMesh water, opaque;
  if (settings.draw_surface) water = reconstruct_surface(loaded.fluid.positions, settings.surface);
  SurfaceScene scene;
  scene.fluid = water.empty() ? nullptr : &water;
  scene.environment = settings.environment;
  scene.water = settings.water;
  for (const SolidMesh& s : loaded.solids) scene.solids.push_back(scene_solid(s)), opaque.append(s.mesh);
  SurfacePassOptions pass_options;
  pass_options.supersample = settings.supersample;
  SurfacePass pass(pass_options);
  const Stopwatch t_bg;
  const ImageRGBf background = pass.render(scene, camera).colour;
  const double background_ms = t_bg.milliseconds();
  VolumeSurfaces surfaces;
  surfaces.water = water.empty() ? nullptr : &water;
  surfaces.solids = opaque.empty() ? nullptr : &opaque;

  float r_min = INFINITY;
  for (const DiffuseLook& look : settings.volume.look)
    if (look.radius > 0) r_min = std::min(r_min, look.radius);

  const int repeats = c.quick ? 1 : 2;
  auto run = [&](VolumeIntegrator integrator, float step, double& ms) {
    VolumeSettings v = settings.volume;
    v.integrator = integrator;
    v.march_step = step;
    v.shutter = 0.0f;  // Eq. 9's integrators compared on the still frame
    // The fastest of `repeats` runs: the machine may be shared, and the first run pays page faults.
    VolumeImage image;
    ms = INFINITY;
    for (int k = 0; k < repeats; ++k) {
      const Stopwatch t0;
      image = render_volume(loaded.diffuse, camera, v, surfaces);
      ms = std::min(ms, t0.milliseconds());
    }
    return image;
  };
  c.progress("render: exact integration (reference)");
  double exact_ms = 0;
  const VolumeImage exact = run(VolumeIntegrator::Exact, 0, exact_ms);
  const ImageRGB8 exact8 = to_srgb8(composite(exact, background));

  r.measures = str("Frame ", frame, " of `", setup.sim.name, "` (its busiest: ", loaded.diffuse.size(),
                   " diffuse particles) at ", settings.width, "x", settings.height, ", ", settings.volume.samples_per_pixel,
                   " ray(s) per pixel; r = ", num(r_min * 1000.0, 3),
                   " mm is the smallest drawn diffuse radius. Errors of the transmittance L over all pixels and of the "
                   "final 8-bit sRGB image (levels 0-255, every channel) are against the exact integration; times are "
                   "the volume pass alone (the surface pass, ", num(background_ms, 3),
                   " ms, is the same for every integrator)");
  r.table.columns = {"integrator", "dx_over_r", "dx_mm", "ms_per_frame", "L_rmse", "L_max_error", "image8_rmse_levels",
                     "image8_max_error_levels"};
  r.table.add_row({"exact", "0", "0", num(exact_ms), "0", "0", "0", "0"});
  const std::vector<double> factors = {2.0, 1.0, 0.5, 0.25, 0.125};
  std::vector<double> dx, l_rms, l_max, rgb_rms, rgb_max, ms_list;
  Series s_lrms{"L, RMSE", {}, true}, s_lmax{"L, max error", {}, true}, s_rgbrms{"8-bit image, RMSE", {}, true},
      s_rgbmax{"8-bit image, max error", {}, true}, s_ms{"march", {}, true}, s_exact{"exact", {}, true, true},
      s_cost{"march: L RMSE", {}, true};
  for (double f : factors) {
    c.progress(str("render: march dx = ", f, " r"));
    double ms = 0;
    const VolumeImage march = run(VolumeIntegrator::March, float(f * r_min), ms);
    const Errors e = compare(march, to_srgb8(composite(march, background)), exact, exact8);
    r.table.add_row({"march", num(f), num(f * r_min * 1000.0), num(ms), num(e.l_rms), num(e.l_max), num(e.rgb_rms),
                     num(e.rgb_max)});
    dx.push_back(f), l_rms.push_back(e.l_rms), l_max.push_back(e.l_max), rgb_rms.push_back(e.rgb_rms), rgb_max.push_back(e.rgb_max), ms_list.push_back(ms);
    s_lrms.points.push_back({f, e.l_rms}), s_lmax.points.push_back({f, e.l_max});
    s_rgbrms.points.push_back({f, e.rgb_rms}), s_rgbmax.points.push_back({f, e.rgb_max});
    s_ms.points.push_back({f, ms}), s_exact.points.push_back({f, exact_ms}), s_cost.points.push_back({ms, e.l_rms});
  }
  std::sort(s_cost.points.begin(), s_cost.points.end());
  const PowerFit fit_l = fit_power_law(dx, l_rms);
  const PowerFit fit_lmax = fit_power_law(dx, l_max);
  const PowerFit fit_rgb = fit_power_law(dx, rgb_rms);
  // The coarsest march whose image matches the exact one to within one 8-bit level RMS.
  std::string within_level = "no step tried";
  for (size_t i = 0; i < dx.size(); ++i)
    if (rgb_rms[i] <= 1.0) {
      within_level = str("dx = ", num(dx[i]), " r (", num(ms_list[i], 3), " ms, ", num(ms_list[i] / exact_ms, 3),
                         "x the exact pass)");
      break;
    }
  r.reading = str("The RMSE of L falls as dx^", num(fit_l.order, 3), " (least-squares fit over ", fit_l.points,
                  " steps, R^2 = ", num(fit_l.r_squared, 3), "), its maximum as dx^", num(fit_lmax.order, 3),
                  " and the 8-bit image RMSE as dx^", num(fit_rgb.order, 3),
                  ": ", order_name(fit_l.order),
                  std::abs(fit_l.order - 1.0) <= 0.2
                      ? ", as sampling an indicator function at fixed steps must be (each chord end is off by up to one "
                        "step)"
                      : ", where sampling an indicator function at fixed steps should give first order",
                  ". Halving dx costs ",
                  num(ms_list[3] / ms_list[2], 3), "x the time between r/2 and r/4. The march's default step (r/2) "
                  "gives L RMSE ", num(l_rms[2], 3), " and ", num(rgb_rms[2], 3), " levels RMS (max ",
                  num(rgb_max[2], 3), " levels) at ",
                  num(ms_list[2], 3), " ms, while the exact integration takes ", num(exact_ms, 3),
                  " ms with no error: the first march within one level RMS of it is ", within_level, ".");
  r.figure.panels = {
      Panel{"Transmittance L: march vs exact", "march step dx (units of r)", "error of L", true, true, false,
            {s_lrms, s_lmax}, 2},
      Panel{"8-bit sRGB image: march vs exact", "march step dx (units of r)", "error (8-bit levels)", true, true, false,
            {s_rgbrms, s_rgbmax}, 2},
      Panel{"Volume pass time", "march step dx (units of r)", "ms per frame", true, true, false, {s_ms, s_exact}, 2},
      Panel{"Error against run time", "ms per frame (volume pass)", "RMSE of L", true, true, false, {s_cost}}};
  r.figure.columns = 2;
  return r;
}

}  // namespace spume::report
