// The real scene part of the diffuse study: the cached diffuse state of one frame stepped through a
// few fluid frames at each substep count, for the printed integrators (spray euler_cromer, bubble
// paper) and spume's defaults (exact, exponential). Emission draws different random numbers at
// each substep count, so only statistics are compared: per-type counts and the particle density
// on a coarse grid.
#include <cmath>

#include "sim/stage/scene_inputs.h"
#include "render/app/scene/scene_args.h"
#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "sim/diffuse/simulator.h"
#include "render/app/report/diffuse_runs.h"
#include "sim/io/spume_cache.h"
#include "sim/stage/diffuse_stage.h"
#include "sim/stage/simulate_scene.h"

namespace spume::report {
namespace {

struct Grid {
  Vec3f origin;
  float cell = 0;
  int nx = 0, ny = 0, nz = 0;
  std::vector<float> count(const DiffuseFrame& f) const {
    std::vector<float> c(size_t(nx) * ny * nz, 0.0f);
    for (const Vec3f& p : f.positions) {
      const Vec3f q = (p - origin) / cell;
      const int i = std::clamp(int(q.x()), 0, nx - 1), j = std::clamp(int(q.y()), 0, ny - 1),
                k = std::clamp(int(q.z()), 0, nz - 1);
      c[(size_t(k) * ny + j) * nx + i] += 1.0f;
    }
    return c;
  }
};

// Where the study counts the material: the tanks with the air above them, else the domain. The domain
// reaches beside an open tank too, for spray on its way to the ground; counting there would only
// coarsen the cells over the water.
Aabb study_region(const SceneInputs& inputs) {
  Aabb box;
  for (const Solid& s : inputs.solids.solids())
    if (s.kind == Solid::Kind::Tank) box.extend(tank_with_air_above(s));
  return box.empty() ? inputs.domain : box;
}

}  // namespace

SceneWindow scene_runs(const StudyContext& c, const SceneSetup& setup, int last, int frames) {
  const SimScene& scene = setup.sim;
  auto source = scene_fluid_source(scene, setup.out_root);
  const std::vector<int> all = diffuse_frames_to_run(scene, *source, DiffuseStageOptions{});
  const int first = std::max(all.front(), last - frames);
  if (first >= last) fail("diffuse study: frame ", last, " has no earlier frame to start from");
  std::vector<FluidFrame> fluid;
  for (int f = first; f <= last; ++f) fluid.push_back(source->load(f));
  const DiffuseFrame start = read_diffuse_cache(diffuse_cache_path(setup.out_root / scene.name, first));

  DiffuseSetup base;
  base.params = scene.diffuse;
  base.fluid = scene.fluid;
  const SceneInputs inputs = read_scene_inputs(scene, setup.out_root, true);
  base.solids = inputs.solids;
  base.domain = inputs.domain;
  // Coarse grid: 16 cells along the study region's longest side.
  const Aabb region = study_region(inputs);
  Grid grid;
  grid.origin = region.min;
  grid.cell = (region.max - region.min).maxCoeff() / 16.0f;
  grid.nx = std::max(1, int(std::ceil((region.max.x() - region.min.x()) / grid.cell)));
  grid.ny = std::max(1, int(std::ceil((region.max.y() - region.min.y()) / grid.cell)));
  grid.nz = std::max(1, int(std::ceil((region.max.z() - region.min.z()) / grid.cell)));

  SceneWindow window;
  window.first = first, window.last = last;
  window.grid_cells = grid.nx * grid.ny * grid.nz;
  window.cell_size = grid.cell;
  struct Config {
    std::string name;
    SprayIntegrator spray;
    BubbleDrag drag;
  };
  const std::vector<Config> configs = {{"as printed", SprayIntegrator::EulerCromer, BubbleDrag::Paper},
                                       {"spume default", SprayIntegrator::Exact, BubbleDrag::Exponential}};
  std::vector<std::pair<int, uint64_t>> plan;
  for (int n : kSubsteps) plan.push_back({n, scene.diffuse.seed});
  plan.push_back({kReferenceSubsteps, scene.diffuse.seed});
  plan.push_back({kReferenceSubsteps, scene.diffuse.seed + 1});
  for (const Config& config : configs)
    for (const auto& [n, seed] : plan) {
      c.progress(str("diffuse: ", scene.name, " frames ", first, "-", last, ", ", config.name, ", ", n,
                     " substeps, seed ", seed));
      DiffuseSetup s = base;
      s.params.substeps = n;
      s.params.seed = seed;
      s.params.spray_integrator = config.spray;
      s.params.bubble_drag = config.drag;
      DiffuseSimulator sim(s);
      sim.set_particles(start);
      SceneRun run{config.name, n, seed, {}, {}, 0.0};
      const Stopwatch t0;
      for (size_t k = 0; k + 1 < fluid.size(); ++k) sim.process_frame(fluid[k], &fluid[k + 1], [](auto&, auto&) {});
      run.ms_per_frame =
          t0.milliseconds() / double(fluid.size() - 1);
      sim.process_frame(fluid.back(), nullptr, [&](const DiffuseFrame& f, const FrameStats&) {
        const auto counts = f.count_by_type();
        run.counts = {counts[0], counts[1], counts[2]};
        run.density = grid.count(f);
      });
      window.runs.push_back(std::move(run));
    }
  return window;
}

}  // namespace spume::report
