#pragma once
// What the stages need to know of a scene's whole fluid sequence before they start: a survey of
// every frame (io/fluid_survey.h; kept in OUT/<scene>/fluid_survey.json), the container when the
// scene asks for it to be inferred, and the domain when the scene gives none. The simulation and the
// render stage both start here, so the domain, the walls and the camera agree for every frame and
// every farm chunk.
#include <filesystem>
#include <string>
#include <vector>

#include "sim/io/fluid_survey.h"
#include "sim/scene/sim_scene.h"

namespace spume {

struct SceneInputs {
  FluidSurvey survey;
  SolidSet solids;   // the scene's, with the inferred tank added; tank walls 2 h thick
  Aabb domain;       // the scene's, else default_domain over the survey's bounds
  std::vector<std::string> notes;  // what was derived, and warnings, one line each
};

// The fluid frames of the scene (its files, or the solver's caches under out_root, which must
// exist), surveyed. Writes the notes to stderr unless quiet, and the warnings among them always
// (core/messages.h). Fluid files too sparse for the radius
// are an error (check_particle_spacing).
SceneInputs read_scene_inputs(const SimScene& scene, const std::filesystem::path& out_root, bool quiet);

// Throws when the fluid's particles (`measured_spacing` apart in a first frame of `particles`, at least
// kSpacingCheckParticles) lie farther apart than the support radius h: with no neighbour, every frame
// would come out empty (no surface, no diffuse material), whatever the other keys. A radius in the
// wrong unit (mm for m) does this; the message gives the radius the spacing implies.
inline constexpr uint64_t kSpacingCheckParticles = 8;
void check_particle_spacing(const FluidSequenceInfo& fluid, float measured_spacing, uint64_t particles);

// The warning for a radius that does not match the cache's spacing (2r expected), or "".
std::string spacing_warning(float particle_radius, float measured_spacing);

}  // namespace spume
