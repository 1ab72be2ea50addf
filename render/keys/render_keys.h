#pragma once
// The render keys of a scene ("render.*"): one declaration each (keys/key_spec.h). Lengths in m,
// colours linear RGB; radii default to multiples of the fluid particle radius r, so a scene with no
// render keys at all still renders something sensible.
#include <array>

#include "sim/keys/key_spec.h"

namespace spume::keys::render {

using enum KeyType;
using enum Scaling;
using enum Bound;

inline constexpr KeySpec resolution{.path = "render.resolution", .type = Size, .unit = "pixels", .value = {960, 540},
                                    .lo = 1, .hi = 16384, .lo_bound = Closed, .hi_bound = Closed,
                                    .doc = "[width, height] of the frames"};
inline constexpr KeySpec spp{.path = "render.spp", .type = Integer, .value = {1}, .lo = 1, .hi = 1024,
                             .lo_bound = Closed, .hi_bound = Closed,
                             .doc = "eye rays per pixel (jittered, deterministic per frame and pixel)"};
inline constexpr KeySpec seed{.path = "render.seed", .type = Integer, .value = {0}, .lo = 0, .hi = 4294967295.0,
                              .lo_bound = Closed, .hi_bound = Closed, .doc = "jitter key, with the frame number"};
inline constexpr KeySpec camera{.path = "render.camera", .type = Object,
                                .default_text = "framed on the tanks and the fluid of the whole sequence",
                                .doc = "{position, target, fov}, or {keys: [{time, position, target, fov}, ...]}"};
inline constexpr KeySpec camera_position{.path = "render.camera.position", .type = Vec3, .unit = "m", .lo = -1e6,
                                         .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                         .default_text = "required", .doc = "camera position"};
inline constexpr KeySpec camera_target{.path = "render.camera.target", .type = Vec3, .unit = "m", .value = {0, 0, 0},
                                       .lo = -1e6, .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                       .doc = "the point looked at (not the position)"};
inline constexpr KeySpec camera_fov{.path = "render.camera.fov", .unit = "degrees", .value = {45}, .lo = 1,
                                    .hi = 170, .lo_bound = Closed, .hi_bound = Closed, .doc = "vertical field of view"};
inline constexpr KeySpec camera_keys{.path = "render.camera.keys", .type = List, .default_text = "one fixed camera",
                                     .doc = "camera keys, interpolated linearly in time"};
inline constexpr KeySpec key_time{.path = "render.camera.keys[].time", .unit = "s", .lo = -1e9, .hi = 1e9,
                                  .lo_bound = Closed, .hi_bound = Closed, .default_text = "required",
                                  .doc = "the key's time, increasing (double)"};
inline constexpr KeySpec key_position{.path = "render.camera.keys[].position", .type = Vec3, .unit = "m",
                                      .lo = -1e6, .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                      .default_text = "required", .doc = "camera position at the key"};
inline constexpr KeySpec key_target{.path = "render.camera.keys[].target", .type = Vec3, .unit = "m",
                                    .value = {0, 0, 0}, .lo = -1e6, .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                    .doc = "the point looked at"};
inline constexpr KeySpec key_fov{.path = "render.camera.keys[].fov", .unit = "degrees", .value = {45}, .lo = 1,
                                 .hi = 170, .lo_bound = Closed, .hi_bound = Closed, .doc = "vertical field of view"};
inline constexpr KeySpec surface{.path = "render.surface", .type = Boolean, .value = {1},
                                 .doc = "draw the fluid surface (reconstruction + OSMesa)"};
inline constexpr KeySpec surface_cell{.path = "render.surface_cell", .unit = "r", .value = {1}, .lo = 0.25, .hi = 4,
                                      .lo_bound = Closed, .hi_bound = Closed, .doc = "marching-cubes cell"};
inline constexpr KeySpec surface_smoothing{.path = "render.surface_smoothing", .type = Integer, .value = {8},
                                           .lo = 0, .hi = 100, .lo_bound = Closed, .hi_bound = Closed,
                                           .doc = "Taubin smoothing iterations of the surface mesh and its normals"};
inline constexpr KeySpec solids{.path = "render.solids", .type = Boolean, .value = {1},
                                .doc = "draw the solids (tanks as cutaways: walls between camera and water left out)"};
inline constexpr KeySpec supersample{.path = "render.supersample", .type = Integer, .value = {1}, .lo = 1, .hi = 4,
                                     .lo_bound = Closed, .hi_bound = Closed,
                                     .doc = "OSMesa pass supersampling per axis (anti-aliasing; 2: about 3x the time)"};
inline constexpr KeySpec integrator{.path = "render.integrator", .type = Choice, .choices = "exact|march",
                                    .doc = "exact: length inside the union of spheres (the dx -> 0 limit); march: Eq. 9"};
inline constexpr KeySpec march_step{.path = "render.march_step", .unit = "m", .value = {0}, .lo = 0, .hi = 1e3,
                                    .lo_bound = Closed, .hi_bound = Closed,
                                    .default_text = "0: half the smallest drawn radius", .doc = "dx of march"};
inline constexpr KeySpec alpha{.path = "render.alpha", .unit = "1/m", .value = {50}, .lo = 0, .hi = 1e9,
                               .lo_bound = Closed, .hi_bound = Closed, .doc = "alpha of Eq. 9"};
// Spray smaller than foam, so it reads sharper (the paper's Sec. 4); bubbles in between, bluish.
inline constexpr KeySpec spray_radius{.path = "render.spray.radius", .unit = "m", .value = {0.3}, .scaling = Radius,
                                      .lo = 0, .hi = 1e3, .lo_bound = Closed, .hi_bound = Closed,
                                      .doc = "sphere radius r_d of spray; 0: not drawn"};
inline constexpr KeySpec spray_color{.path = "render.spray.color", .type = Colour, .value = {0.92, 0.95, 1.0},
                                     .lo = 0, .hi = 100, .lo_bound = Closed, .hi_bound = Closed,
                                     .doc = "diffuse colour C_d of spray"};
inline constexpr KeySpec foam_radius{.path = "render.foam.radius", .unit = "m", .value = {0.5}, .scaling = Radius,
                                     .lo = 0, .hi = 1e3, .lo_bound = Closed, .hi_bound = Closed,
                                     .doc = "sphere radius of foam; 0: not drawn"};
inline constexpr KeySpec foam_color{.path = "render.foam.color", .type = Colour, .value = {0.95, 0.95, 0.95},
                                    .lo = 0, .hi = 100, .lo_bound = Closed, .hi_bound = Closed,
                                    .doc = "colour of foam"};
inline constexpr KeySpec bubble_radius{.path = "render.bubble.radius", .unit = "m", .value = {0.4},
                                       .scaling = Radius, .lo = 0, .hi = 1e3, .lo_bound = Closed, .hi_bound = Closed,
                                       .doc = "sphere radius of bubbles; 0: not drawn"};
inline constexpr KeySpec bubble_color{.path = "render.bubble.color", .type = Colour, .value = {0.80, 0.90, 1.0},
                                      .lo = 0, .hi = 100, .lo_bound = Closed, .hi_bound = Closed,
                                      .doc = "colour of bubbles"};
inline constexpr KeySpec water_absorption{
    .path = "render.water.absorption", .type = Vec3, .unit = "1/m", .value = {3.5, 1.1, 0.75}, .lo = 0, .hi = 1e6,
    .lo_bound = Closed, .hi_bound = Closed,
    .doc = "Beer-Lambert absorption per channel, in both passes (about 5x clear sea water, so tank-sized "
           "scenes read as water)"};
inline constexpr KeySpec water_ior{.path = "render.water.ior", .value = {1.333}, .lo = 1, .hi = 3, .lo_bound = Closed,
                                   .hi_bound = Closed, .doc = "refractive index (Schlick F0 = 0.02)"};
inline constexpr KeySpec water_roughness{.path = "render.water.roughness", .value = {0.04}, .lo = 0.001, .hi = 1,
                                         .lo_bound = Closed, .hi_bound = Closed,
                                         .doc = "GGX alpha of the sun's highlight"};
inline constexpr KeySpec water_deep_color{.path = "render.water.deep_color", .type = Colour,
                                          .value = {0.012, 0.055, 0.075}, .lo = 0, .hi = 100, .lo_bound = Closed,
                                          .hi_bound = Closed, .doc = "radiance of water seen through an infinite depth"};
inline constexpr KeySpec water_refraction{.path = "render.water.refraction", .value = {1}, .lo = 0, .hi = 1,
                                          .lo_bound = Closed, .hi_bound = Closed,
                                          .doc = "0: straight-through view of the bottom; 1: the physical bend"};
inline constexpr KeySpec water_scene_reflections{.path = "render.water.scene_reflections", .type = Boolean,
                                                 .value = {1},
                                                 .doc = "reflect the ground and solids (screen space); false: sky only"};
inline constexpr KeySpec ground{.path = "render.ground", .type = Boolean, .value = {1}, .doc = "draw a ground plane"};
inline constexpr KeySpec ground_height{.path = "render.ground_height", .unit = "m", .lo = -1e6, .hi = 1e6,
                                       .lo_bound = Closed, .hi_bound = Closed,
                                       .default_text = "just below the lowest solid or particle",
                                       .doc = "the ground plane's height"};
inline constexpr KeySpec sun_direction{.path = "render.sun_direction", .type = Vec3, .value = {-0.45, 0.62, 0.64},
                                       .lo = -1e6, .hi = 1e6, .lo_bound = Closed, .hi_bound = Closed,
                                       .doc = "direction towards the sun (normalised)"};
inline constexpr KeySpec frames{.path = "render.frames", .type = Text, .choices = "frames/%04d.png",
                                .doc = "output pattern under OUT/<scene>/ (%04d, %d or ####), ending in .png"};
inline constexpr KeySpec shutter{.path = "render.shutter", .unit = "frames", .value = {0}, .lo = 0, .hi = 1,
                                 .lo_bound = Closed, .hi_bound = Closed,
                                 .doc = "motion blur of the diffuse material: the shutter's open time, centred on the "
                                        "frame (0.5: a 180-degree shutter; 0: still)"};
inline constexpr KeySpec exr{.path = "render.exr", .type = Boolean, .value = {0},
                             .doc = "also write each frame as multilayer OpenEXR beside its PNG (.exr): half-float "
                                    "linear beauty, Z, and a layer per element (README: EXR frames)"};

inline constexpr auto all = std::to_array<const KeySpec*>(
    {&resolution, &spp, &seed, &camera, &camera_position, &camera_target, &camera_fov, &camera_keys, &key_time,
     &key_position, &key_target, &key_fov, &surface, &surface_cell, &surface_smoothing, &solids, &supersample,
     &integrator, &march_step, &alpha, &spray_radius, &spray_color, &foam_radius, &foam_color, &bubble_radius,
     &bubble_color, &water_absorption, &water_ior, &water_roughness, &water_deep_color, &water_refraction,
     &water_scene_reflections, &ground, &ground_height, &sun_direction, &frames, &shutter, &exr});

}  // namespace spume::keys::render
