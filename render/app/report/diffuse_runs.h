#pragma once
// The two halves of the diffuse time-integration study (study_diffuse.cpp puts them together).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/diffuse/params.h"
#include "render/app/report/study.h"

namespace spume {
struct SceneSetup;
}

namespace spume::report {

inline const std::vector<int> kSubsteps = {1, 2, 4, 8, 16};
constexpr int kReferenceSubsteps = 64;

// One integrator of one analytic case at one substep count.
struct AnalyticRun {
  std::string integrator;   // "spray euler_cromer", "bubble exponential", ...
  int substeps = 0;
  double error_reference = 0;  // m, |x - x(64 substeps)| at the horizon
  double error_exact = 0;      // m, |x - closed form|
  double ms_per_frame = 0;     // per million particles
};

// Spray in free fall and a bubble rising in a uniform fluid velocity with drag, over `horizon` s at
// the frame rate `fps`, with the scene's buoyancy, drag and reference step; every integrator.
std::vector<AnalyticRun> analytic_runs(const DiffuseParams& scene_params, double fps, double horizon, int particles);

// One configuration of the real scene at one substep count.
struct SceneRun {
  std::string config;     // "as printed" or "spume default"
  int substeps = 0;
  uint64_t seed = 0;
  std::array<size_t, 3> counts{};  // spray, foam, bubbles at the last frame
  std::vector<float> density;      // particles per coarse-grid cell at the last frame
  double ms_per_frame = 0;
};

struct SceneWindow {
  int first = 0, last = 0;  // frames: the diffuse cache of `first` is the start, `last` is compared
  std::vector<SceneRun> runs;
  int grid_cells = 0;
  double cell_size = 0;     // m
};

// Runs both configurations at kSubsteps and kReferenceSubsteps (and the reference again with
// another seed: the noise floor of statistics that depend on random draws) from the cached frame
// `last - frames` to `last`.
SceneWindow scene_runs(const StudyContext& context, const SceneSetup& setup, int last, int frames);

}  // namespace spume::report
