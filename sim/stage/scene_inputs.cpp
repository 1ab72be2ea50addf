#include "sim/stage/scene_inputs.h"

#include <cstdio>

#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/io/frame_pattern.h"
#include "sim/stage/fluid_stage.h"
#include "sim/scene/container.h"
#include "sim/scene/tank_fit.h"
#include "sim/scene/velocity_check.h"
#include "sim/io/fluid_source.h"

namespace spume {
namespace {

std::string describe_box(const Aabb& b) {
  return str("[", b.min.x(), ", ", b.min.y(), ", ", b.min.z(), "] - [", b.max.x(), ", ", b.max.y(), ", ", b.max.z(),
             "]");
}

int up_axis(const Vec3f& gravity) {
  int up = 1;
  if (gravity.norm() > 0.0f) gravity.cwiseAbs().maxCoeff(&up);
  return up;
}

}  // namespace

std::string spacing_warning(float particle_radius, float measured_spacing) {
  if (!(measured_spacing > 0.0f)) return "";
  const float ratio = measured_spacing / (2.0f * particle_radius);
  if (ratio > 0.67f && ratio < 1.5f) return "";
  return str("warning: fluid.radius ", particle_radius, " m implies a particle spacing of ", 2.0f * particle_radius,
             " m, but the fluid's particles lie ", measured_spacing, " m from their nearest neighbour (",
             ratio, " times that); neighbour counts, thresholds and the emission will be wrong. Set fluid.radius "
             "(--radius) to about ", 0.5f * measured_spacing, " m");
}

void check_particle_spacing(const FluidSequenceInfo& fluid, float measured_spacing, uint64_t particles) {
  const float h = fluid.support_radius;
  // A handful of particles (an emitter's first drops) says little about the spacing of the fluid.
  if (particles < kSpacingCheckParticles || !(measured_spacing >= h)) return;
  fail("fluid.radius ", fluid.particle_radius, " m (--radius): the fluid's particles lie ", measured_spacing,
       " m from their nearest neighbour (median of the first frame), ", measured_spacing / (2.0f * fluid.particle_radius),
       " times the spacing 2 r = ", 2.0f * fluid.particle_radius, " m this radius implies and beyond the support radius h = ",
       h, " m: no particle would have a neighbour, so the water would have no surface and no spray, foam or bubbles "
       "could form. Set fluid.radius (--radius) to about ", 0.5f * measured_spacing, " m (half the spacing)");
}

SceneInputs read_scene_inputs(const SimScene& scene, const std::filesystem::path& out_root, bool quiet) {
  SceneInputs in;
  const std::filesystem::path scene_out = out_root / scene.name;
  const bool solver = scene.source == FluidSourceKind::Solver;
  const std::string pattern = solver ? fluid_cache_pattern(scene_out) : scene.file_pattern;
  std::vector<int> frames;
  for (int f : find_pattern_frames(pattern))
    if (!scene.frames || (f >= scene.frames->first && f <= scene.frames->second)) frames.push_back(f);
  if (frames.empty())
    fail(pattern, ": no fluid frames", scene.frames ? str(" within frames ", scene.frames->first, "-",
                                                           scene.frames->second) : std::string());
  std::error_code ec;
  std::filesystem::create_directories(scene_out, ec);
  in.survey = survey_fluid_files(pattern, frames, fluid_survey_path(scene_out), quiet,
                                 solver ? FluidReadOptions{} : scene.read);
  in.notes = scene.import_notes;
  in.notes.insert(in.notes.end(), in.survey.notes.begin(), in.survey.notes.end());

  if (const std::vector<int> missing = missing_frames(frames); !missing.empty() && scene.allow_gaps)
    in.notes.push_back(str("fluid.allow_gaps: ", missing.size(), " missing fluid frame", missing.size() > 1 ? "s" : "",
                           " (the first is ", missing.front(), ") interpolated between the frames on either side"));
  if (!solver) {
    // The radius first: every later check (tank walls within 2r, inferred planes) is measured in it.
    check_particle_spacing(scene.fluid, in.survey.spacing, in.survey.frames.front().particles);
    const std::string warning = spacing_warning(scene.fluid.particle_radius, in.survey.spacing);
    if (!warning.empty()) in.notes.push_back(warning);
    const VelocityCheck velocities = check_stored_velocities(in.survey, scene.fluid.fps, scene.fluid.particle_radius,
                                                             scene.velocity_scale, scene.gravity);
    if (!velocities.note.empty()) in.notes.push_back(velocities.note);
    // A doubt about the units (Mantaflow's names without its config) is settled by that measurement.
    if (!scene.velocity_units_doubt.empty())
      in.notes.push_back(velocities.agrees ? "velocities: used as stored (no Mantaflow config to convert them, and the "
                                             "check above finds them right)"
                                           : scene.velocity_units_doubt);
  }
  in.solids = scene.solids;
  if (!solver) {
    // Before a tank is inferred: only the tanks the scene gives are checked.
    const std::string warning = check_tanks_hold_fluid(in.survey, in.solids, scene.fluid.particle_radius);
    if (!warning.empty()) in.notes.push_back(warning);
  }
  if (scene.infer_container != TankInference::Off) {
    const InferredContainer c = infer_container(in.survey, scene.fluid.particle_radius, up_axis(scene.gravity));
    if (!c.tank && scene.infer_container == TankInference::Required)
      fail("solids: the tank to infer (\"infer\": true, or --tank auto): ", c.summary,
           "; give the tank's min and max instead, or leave the tank out (--tank none)");
    // Without --tank, only a closed tank is used: an open side would put a far wall (sim/scene/container.h)
    // where nothing was seen, and the camera would frame it.
    const bool use = c.tank && (scene.infer_container == TankInference::Required || c.closed);
    if (scene.infer_container == TankInference::Required)
      in.notes.push_back(c.summary);
    else if (use)
      in.notes.push_back(str(c.summary, "; used since no --tank was given (--tank none runs without it)"));
    else if (c.tank)
      in.notes.push_back(str(c.summary, "; not used, since a side is open (--tank auto uses it with that side far away; "
                                        "or give the tank with --tank X0,Y0,Z0,X1,Y1,Z1)"));
    else
      in.notes.push_back(str(c.summary, "; running without a tank (give one with --tank X0,Y0,Z0,X1,Y1,Z1)"));
    if (use) {
      std::vector<Solid> solids = in.solids.solids();
      solids.push_back(*c.tank);
      in.solids = SolidSet(std::move(solids));
    }
  }
  {
    // For the diffuse material, a tank's walls are 2 h thick: spray that leaves over the rim and
    // falls beyond them is outside (the domain then deletes it), not pulled back in through the wall.
    std::vector<Solid> solids = in.solids.solids();
    for (Solid& s : solids)
      if (s.kind == Solid::Kind::Tank) s.wall_thickness = 2.0f * scene.fluid.support_radius;
    in.solids = SolidSet(std::move(solids));
  }

  SimScene resolved = scene;
  resolved.solids = in.solids;
  if (!scene.domain.empty()) {
    in.domain = scene.domain;
  } else {
    in.domain = default_domain(resolved, in.survey.bounds());
    const bool tank = std::any_of(in.solids.solids().begin(), in.solids.solids().end(),
                                  [](const Solid& s) { return s.kind == Solid::Kind::Tank; });
    in.notes.push_back(str("domain (diffuse particles leaving it are deleted): ", describe_box(in.domain),
                           tank ? ", the tanks (an open one widened on each side and raised by its height, "
                                  "for spray thrown over the rim)"
                                : str(", the fluid's bounds over all ", frames.size(),
                                      " frames grown by their size on every side"),
                           "; set domain.min and domain.max to change it"));
  }
  // Warnings whatever `quiet` says (messages.h): a farm job runs quiet.
  for (const std::string& note : in.notes)
    if (messages::is_warning(note)) messages::warning(note);
    else if (!quiet) messages::note(note);
  return in;
}

}  // namespace spume
