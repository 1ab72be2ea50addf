#pragma once
// The simulation keys of a scene: the scene itself, the fluid (files or spume's solver), the solver's
// settings, the solids, the domain and the outputs. SI units.
#include <array>

#include "sim/keys/key_spec.h"

namespace spume::keys {

using enum KeyType;
using enum Scaling;
using enum Bound;

namespace scene {
inline constexpr KeySpec name{.path = "name", .type = Text, .default_text = "the scene file's stem",
                              .doc = "output folder name: OUT/<name>/ (letters, digits, _ - .)"};
inline constexpr KeySpec gravity{.path = "gravity", .type = Vec3, .unit = "m/s^2", .value = {0, -9.81, 0},
                                 .lo = -1e4, .hi = 1e4, .lo_bound = Closed, .hi_bound = Closed,
                                 .doc = "gravity; the renderer's sky and ground need it along -y"};
inline constexpr auto all = std::to_array<const KeySpec*>({&name, &gravity});
}  // namespace scene

namespace fluid {
inline constexpr KeySpec source{.path = "fluid.source", .type = Choice, .choices = "files|solver",
                                .doc = "particle files, or spume's DFSPH solver"};
inline constexpr KeySpec files{.path = "fluid.files", .type = Text, .default_text = "required with \"files\"",
                               .doc = "particle file pattern (%d, %04d, #### or $F, $F4), relative to the scene file"};
inline constexpr KeySpec radius{.path = "fluid.radius", .unit = "m", .lo = 1e-5, .hi = 10, .lo_bound = Closed,
                                .hi_bound = Closed, .default_text = "required",
                                .doc = "the fluid particle radius r (the particles' spacing is 2 r)"};
inline constexpr KeySpec support_radius{.path = "fluid.support_radius", .unit = "m", .value = {4}, .scaling = Radius,
                                        .lo = 0, .hi = 100, .lo_bound = Open, .hi_bound = Closed,
                                        .doc = "influence radius h (the solver uses 4 r)"};
// h as a multiple of r: the declared default, which the fluid solver's kernel always uses and the
// renderer's surface field too. The factor is written once, in the declaration above.
inline constexpr float kSupportFactor = float(support_radius.value[0]);
// h = 4 r for particle radius r (exact in float: a power of two times r).
inline constexpr float support_radius_of(float r) { return kSupportFactor * r; }
inline constexpr KeySpec fps{.path = "fluid.fps", .unit = "1/s", .value = {50}, .lo = 1e-3, .hi = 1e5,
                             .lo_bound = Closed, .hi_bound = Closed,
                             .doc = "frames per second of the fluid frames (stored as double); files: a "
                                    "Mantaflow cache's config gives it when not set, and one that disagrees stops"};
inline constexpr KeySpec rest_density{.path = "fluid.rest_density", .unit = "kg/m^3", .value = {1000}, .lo = 0,
                                      .hi = 1e6, .lo_bound = Open, .hi_bound = Closed,
                                      .doc = "rho0; uniform particle mass rho0 (2r)^3 when files carry none, or "
                                             "masses off by more than 2x from it (warned)"};
inline constexpr KeySpec frames{.path = "fluid.frames", .type = Range, .value = {0, 100}, .lo = 0, .hi = 1e8,
                                .lo_bound = Closed, .hi_bound = Closed,
                                .default_text = "solver, from t = 0; files: every file found",
                                .doc = "[first, last] whole frame numbers to use"};
inline constexpr KeySpec allow_gaps{.path = "fluid.allow_gaps", .type = Boolean, .value = {0},
                                    .doc = "files: interpolate missing frames between their neighbours (else "
                                           "a missing frame is an error naming it)"};
inline constexpr KeySpec velocity_scale{
    .path = "fluid.velocity_scale", .value = {1}, .lo = 0, .hi = 1e6, .lo_bound = Open, .hi_bound = Closed,
    .doc = "files: factor on the stored velocities, for caches in other units (the log measures them against "
           "the motion); a Mantaflow cache's grid units are converted from its config unless given"};
inline constexpr KeySpec up_axis{
    .path = "fluid.up_axis", .type = Choice, .choices = "auto|y|z",
    .doc = "files: the cache's up axis; z turns (x, y, z) into spume's Y-up (x, z, -y); auto is z for a Blender "
           "Mantaflow cache (config/ beside data/), y for Houdini's formats, else measured (a free fall, a "
           "resting layer), else y"};
inline constexpr KeySpec vdb_grid{.path = "fluid.vdb_grid", .type = Text, .default_text = "every point data grid",
                                  .doc = "files: the point data grid of a .vdb cache to read, by name"};
inline constexpr KeySpec particles{
    .path = "fluid.particles", .type = Choice, .choices = "auto|sph|flip",
    .doc = "what the cached particles are: sph (the paper's model as is) or flip (velocities averaged over 2 h "
           "for the potentials, counts measured against the frame's own particle density; MODEL.md §9); auto is "
           "flip for a Blender Mantaflow cache, else sph"};
inline constexpr KeySpec narrow_band{
    .path = "fluid.narrow_band", .type = Choice, .choices = "auto|off",
    .doc = "auto: a frame whose particles enclose a large empty interior (a FLIP cache that keeps only a band "
           "near the surface) is filled there for classification and advection (MODEL.md §9); off: taken as is"};
inline constexpr KeySpec blocks{.path = "fluid.blocks", .type = List, .default_text = "required with \"solver\"",
                                .doc = "solver: the initial fluid, cuboids filled on a lattice of spacing 2 r"};
inline constexpr KeySpec block_min{.path = "fluid.blocks[].min", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                                   .lo_bound = Closed, .hi_bound = Closed, .default_text = "required",
                                   .doc = "a block's lower corner"};
inline constexpr KeySpec block_max{.path = "fluid.blocks[].max", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                                   .lo_bound = Closed, .hi_bound = Closed, .default_text = "required",
                                   .doc = "a block's upper corner, above min on every axis"};
inline constexpr auto all = std::to_array<const KeySpec*>(
    {&source, &files, &radius, &support_radius, &fps, &rest_density, &frames, &allow_gaps, &velocity_scale, &up_axis,
     &vdb_grid, &particles, &narrow_band, &blocks, &block_min, &block_max});
}  // namespace fluid

// Solver settings (fluid.solver.*): sim/fluid/fluid_params.h explains each choice.
namespace solver {
inline constexpr KeySpec viscosity{.path = "fluid.solver.viscosity", .unit = "m^2/s", .value = {1e-3}, .lo = 0,
                                   .hi = 10, .lo_bound = Closed, .hi_bound = Closed,
                                   .doc = "kinematic viscosity of the SPH Laplacian; damps particle noise"};
inline constexpr KeySpec boundary_viscosity{.path = "fluid.solver.boundary_viscosity", .unit = "m^2/s",
                                            .value = {1.5e-3}, .lo = 0, .hi = 10, .lo_bound = Closed,
                                            .hi_bound = Closed, .doc = "wall friction; 0 = free-slip walls"};
inline constexpr KeySpec xsph{.path = "fluid.solver.xsph", .value = {0}, .lo = 0, .hi = 1, .lo_bound = Closed,
                              .hi_bound = Closed, .doc = "XSPH velocity smoothing per step; 0 = off"};
inline constexpr KeySpec cfl{.path = "fluid.solver.cfl", .value = {0.4}, .lo = 1e-3, .hi = 1, .lo_bound = Closed,
                             .hi_bound = Closed, .doc = "dt = cfl x 2 r / fastest speed"};
inline constexpr KeySpec min_dt{.path = "fluid.solver.min_dt", .unit = "s", .value = {1e-5}, .lo = 1e-9, .hi = 1,
                                .lo_bound = Closed, .hi_bound = Closed, .doc = "smallest time step (double)"};
inline constexpr KeySpec max_dt{.path = "fluid.solver.max_dt", .unit = "s", .value = {5e-3}, .lo = 1e-9, .hi = 1,
                                .lo_bound = Closed, .hi_bound = Closed,
                                .doc = "largest time step, at least min_dt (double); depth_cfl may ask for less"};
inline constexpr KeySpec depth_cfl{.path = "fluid.solver.depth_cfl", .value = {0.55}, .lo = 0, .hi = 10,
                                   .lo_bound = Closed, .hi_bound = Closed,
                                   .doc = "dt <= depth_cfl x 2 r / sqrt(|g| D), D the starting fluid's depth: "
                                          "deep water's step (0 = off; README: Deep water)"};
inline constexpr KeySpec density_tolerance{.path = "fluid.solver.density_tolerance", .value = {5e-4}, .lo = 1e-7,
                                           .hi = 0.1, .lo_bound = Closed, .hi_bound = Closed,
                                           .doc = "average compression the density solve stops at"};
inline constexpr KeySpec min_density_iterations{.path = "fluid.solver.min_density_iterations", .type = Integer,
                                                .value = {2}, .lo = 0, .hi = 100000, .lo_bound = Closed,
                                                .hi_bound = Closed, .doc = "density solve: at least"};
inline constexpr KeySpec max_density_iterations{.path = "fluid.solver.max_density_iterations", .type = Integer,
                                                .value = {100}, .lo = 1, .hi = 100000, .lo_bound = Closed,
                                                .hi_bound = Closed, .doc = "density solve: at most"};
inline constexpr KeySpec divergence_solve{.path = "fluid.solver.divergence_solve", .type = Boolean, .value = {1},
                                          .doc = "run DFSPH's divergence-free solve"};
inline constexpr KeySpec divergence_tolerance{.path = "fluid.solver.divergence_tolerance", .value = {1e-3},
                                              .lo = 1e-7, .hi = 0.1, .lo_bound = Closed, .hi_bound = Closed,
                                              .doc = "average compression rate x dt it stops at"};
inline constexpr KeySpec min_divergence_iterations{.path = "fluid.solver.min_divergence_iterations",
                                                   .type = Integer, .value = {1}, .lo = 0, .hi = 100000,
                                                   .lo_bound = Closed, .hi_bound = Closed,
                                                   .doc = "divergence solve: at least"};
inline constexpr KeySpec max_divergence_iterations{.path = "fluid.solver.max_divergence_iterations",
                                                   .type = Integer, .value = {100}, .lo = 1, .hi = 100000,
                                                   .lo_bound = Closed, .hi_bound = Closed,
                                                   .doc = "divergence solve: at most"};
inline constexpr KeySpec warm_start{.path = "fluid.solver.warm_start", .type = Boolean, .value = {0},
                                    .doc = "start each solve from half the previous step's pressure"};
inline constexpr KeySpec boundary_spacing{.path = "fluid.solver.boundary_spacing", .unit = "r", .value = {2},
                                          .lo = 0.5, .hi = 2, .lo_bound = Closed, .hi_bound = Closed,
                                          .doc = "lattice spacing of the boundary particles filling solids"};
inline constexpr KeySpec push_out_skin{.path = "fluid.solver.push_out_skin", .unit = "r", .value = {1}, .lo = 0,
                                       .hi = 1, .lo_bound = Closed, .hi_bound = Closed,
                                       .doc = "a particle found inside a solid goes this far outside it (more "
                                              "adds energy)"};
inline constexpr KeySpec start_clearance{.path = "fluid.solver.start_clearance", .unit = "r", .value = {0.5}, .lo = 0,
                                         .hi = 4, .lo_bound = Closed, .hi_bound = Closed,
                                         .doc = "starting lattice points closer than this to a box or sphere are "
                                                "left out, so none overlaps the solid's samples and is flung out "
                                                "(0: only those inside; README: Deep water)"};
inline constexpr KeySpec wall_pressure{.path = "fluid.solver.wall_pressure", .type = Choice,
                                       .choices = "extrapolated|own",
                                       .doc = "the pressure a wall pushes back with: the fluid's beside it plus the "
                                              "hydrostatic rise (Adami et al. 2012), or each fluid particle's own "
                                              "(Akinci et al. 2012; deep water churns along the walls)"};
inline constexpr auto all = std::to_array<const KeySpec*>(
    {&viscosity, &boundary_viscosity, &xsph, &cfl, &min_dt, &max_dt, &depth_cfl, &density_tolerance,
     &min_density_iterations, &max_density_iterations, &divergence_solve, &divergence_tolerance, &min_divergence_iterations,
     &max_divergence_iterations, &warm_start, &boundary_spacing, &push_out_skin, &start_clearance,
     &wall_pressure});
}  // namespace solver

namespace solids {
inline constexpr KeySpec list{.path = "solids", .type = List, .default_text = "none",
                              .doc = "tanks hold the fluid; boxes and spheres are obstacles"};
inline constexpr KeySpec type{.path = "solids[].type", .type = Choice, .choices = "tank|box|sphere",
                              .doc = "a hollow box, a solid box or a solid sphere"};
inline constexpr KeySpec infer{.path = "solids[].infer", .type = Boolean, .value = {0},
                               .doc = "tank, fluid files only: the walls the fluid was seen stopped at, found from it"};
inline constexpr KeySpec min{.path = "solids[].min", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                             .lo_bound = Closed, .hi_bound = Closed, .default_text = "required (tank, box)",
                             .doc = "lower corner"};
inline constexpr KeySpec max{.path = "solids[].max", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                             .lo_bound = Closed, .hi_bound = Closed, .default_text = "required (tank, box)",
                             .doc = "upper corner, above min on every axis"};
inline constexpr KeySpec open_top{.path = "solids[].open_top", .type = Boolean, .value = {1},
                                  .doc = "tank: no lid (its up axis is opposite gravity)"};
inline constexpr KeySpec center{.path = "solids[].center", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                                .lo_bound = Closed, .hi_bound = Closed, .default_text = "required (sphere)",
                                .doc = "sphere centre"};
inline constexpr KeySpec radius{.path = "solids[].radius", .unit = "m", .lo = 0, .hi = 1e6, .lo_bound = Open,
                                .hi_bound = Closed, .default_text = "required (sphere)", .doc = "sphere radius"};
inline constexpr KeySpec rotation_axis{.path = "solids[].rotation.axis", .type = Vec3, .lo = -1e6, .hi = 1e6,
                                       .lo_bound = Closed, .hi_bound = Closed, .default_text = "required",
                                       .doc = "boxes: rotation axis about the box's centre (normalised)"};
inline constexpr KeySpec rotation_angle{.path = "solids[].rotation.angle", .unit = "rad", .lo = -1e3, .hi = 1e3,
                                        .lo_bound = Closed, .hi_bound = Closed, .default_text = "required",
                                        .doc = "rotation angle"};
inline constexpr KeySpec motion_type{.path = "solids[].motion.type", .type = Choice, .choices = "sine|keyframes",
                                     .doc = "kinematic translation: a sine, or piecewise-linear keyframes"};
inline constexpr KeySpec motion_axis{.path = "solids[].motion.axis", .type = Vec3, .value = {1, 0, 0}, .lo = -1e6,
                                     .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                     .doc = "sine: direction (normalised)"};
inline constexpr KeySpec motion_amplitude{.path = "solids[].motion.amplitude", .unit = "m", .value = {0}, .lo = 0,
                                          .hi = 1e3, .lo_bound = Closed, .hi_bound = Closed,
                                          .doc = "sine: amplitude"};
inline constexpr KeySpec motion_frequency{.path = "solids[].motion.frequency", .unit = "Hz", .value = {0}, .lo = 0,
                                          .hi = 1e3, .lo_bound = Closed, .hi_bound = Closed,
                                          .doc = "sine: frequency"};
inline constexpr KeySpec motion_phase{.path = "solids[].motion.phase", .unit = "rad", .value = {0}, .lo = -1e6,
                                      .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed, .doc = "sine: phase"};
inline constexpr KeySpec motion_start{.path = "solids[].motion.start", .unit = "s", .value = {0}, .lo = 0,
                                      .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                      .doc = "sine: at rest before this time (double)"};
inline constexpr KeySpec keys_time{.path = "solids[].motion.keys[].time", .unit = "s", .lo = -1e9, .hi = 1e9,
                                   .lo_bound = Closed, .hi_bound = Closed, .default_text = "required",
                                   .doc = "keyframes: time, increasing (double)"};
inline constexpr KeySpec keys_offset{.path = "solids[].motion.keys[].offset", .type = Vec3, .unit = "m",
                                     .lo = -1e6, .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                     .default_text = "required", .doc = "keyframes: offset of the solid"};
inline constexpr KeySpec density{.path = "solids[].dynamic.density", .unit = "kg/m^3", .lo = 0, .hi = 1e6,
                                 .lo_bound = Open, .hi_bound = Closed, .default_text = "density or mass",
                                 .doc = "dynamic (boxes, spheres; solver scenes): a rigid body this dense"};
inline constexpr KeySpec mass{.path = "solids[].dynamic.mass", .unit = "kg", .lo = 0, .hi = 1e9, .lo_bound = Open,
                              .hi_bound = Closed, .default_text = "density or mass",
                              .doc = "dynamic: the body's mass instead of a density"};
inline constexpr KeySpec friction{.path = "solids[].dynamic.friction", .value = {0.5}, .lo = 0, .hi = 100,
                                  .lo_bound = Closed, .hi_bound = Closed,
                                  .doc = "dynamic: Coulomb friction in contacts with other solids"};
inline constexpr auto all = std::to_array<const KeySpec*>(
    {&list, &type, &infer, &min, &max, &open_top, &center, &radius, &rotation_axis, &rotation_angle, &motion_type,
     &motion_axis, &motion_amplitude, &motion_frequency, &motion_phase, &motion_start, &keys_time, &keys_offset,
     &density, &mass, &friction});
}  // namespace solids

namespace domain {
inline constexpr KeySpec min{.path = "domain.min", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                             .lo_bound = Closed, .hi_bound = Closed,
                             .default_text = "the tanks (an open one widened and raised by its height), else the fluid's "
                                             "bounds over every frame grown by their size (at least 8 h)",
                             .doc = "diffuse particles outside [min, max] are deleted"};
inline constexpr KeySpec max{.path = "domain.max", .type = Vec3, .unit = "m", .lo = -1e6, .hi = 1e6,
                             .lo_bound = Closed, .hi_bound = Closed, .default_text = "see domain.min",
                             .doc = "upper corner, above min on every axis"};
inline constexpr auto all = std::to_array<const KeySpec*>({&min, &max});
}  // namespace domain

// The exports: written from the caches after the stages, each with a record of its own
// (io/frame_export.h), so turning one on or off re-simulates nothing (no stage's keys hold them).
namespace output {
inline constexpr KeySpec bgeo{.path = "output.bgeo", .type = Boolean, .value = {0},
                              .doc = "also write the diffuse frames as BGEO (Houdini)"};
inline constexpr KeySpec fluid_bgeo{.path = "output.fluid_bgeo", .type = Boolean, .value = {0},
                                    .doc = "solver scenes: also write the fluid frames as BGEO"};
inline constexpr KeySpec vdb{.path = "output.vdb", .type = Boolean, .value = {0},
                             .doc = "also write the diffuse frames as OpenVDB points (Houdini; positions within "
                                    "2 r / 131070, velocities as half floats)"};
// Made by render and run, which know the radii the diffuse material is drawn with (io/fog_volumes.h).
inline constexpr KeySpec fog{.path = "output.fog", .unit = "m", .value = {0}, .lo = 0, .hi = 1e3,
                             .lo_bound = Closed, .hi_bound = Closed,
                             .doc = "voxel size of fog volumes (OpenVDB: spray, foam, bubble, density, v) of the "
                                    "diffuse frames as drawn, written by render and run; 0: none"};
inline constexpr auto all = std::to_array<const KeySpec*>({&bgeo, &fluid_bgeo, &vdb, &fog});
}  // namespace output

}  // namespace spume::keys
