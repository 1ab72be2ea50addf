#pragma once
// GLSL 4.50 core sources of the surface pass, embedded as strings. Every program sees the blocks
// `Env` (binding 0, environment.h) and `Frame` (binding 1, FrameBlock below) and writes linear RGB to
// colour attachment 0 and the linear view depth (m along the view axis) to attachment 1.
#include <string>

namespace spume::shaders {

// std140 mirror of the GLSL `Frame` block.
struct FrameBlock {
  float view_proj[16];      // world -> clip, column-major
  float inv_view[16];       // view -> world
  float inv_view_proj[16];  // clip -> world
  float eye[4];             // camera position, m
  float proj[4];            // x = P00, y = P11 (negative: drawn upside down); z, w = near and far planes, m
  float viewport[4];        // x, y = size in pixels; z, w = reciprocals
  float sun_view_proj[16];  // world -> sun shadow clip space
  float shadow[4];          // x = on, y = shadow-map texel in uv, w = texel in m
};

// The `#version` line, the `Frame` block and positive_infinity(); then the same plus the `Env` block
// and sun_visibility() (every fragment shader that shades).
std::string frame_block_glsl();
std::string fragment_header();

std::string sky_vertex();       // full-screen triangle, no inputs
std::string sky_fragment();     // env_sky along the pixel's view ray; depth +inf
std::string mesh_vertex();      // world position, normal, view depth; uniform vec3 u_offset
std::string solid_fragment();   // diffuse solids (u_albedo), two-sided, shadowed
std::string ground_fragment();  // the ground plane, shadowed
std::string depth_only_fragment();  // nothing but the depth buffer (water back faces)
// The water (water_shader.cpp): its front faces' normal and linear depth (attachments 0, 1), then
// shading, a full-screen pass: samplers at units 0-2 (opaque colour and depth, back-face depth) and
// 4, 5 (the front faces' normal and depth).
std::string water_normal_fragment();
std::string water_fragment();
// Supersampling: box-filters u_ss x u_ss texels of the final targets into attachments 0 (colour,
// averaged), 1 (depth) and 2 (opaque depth; the depths take the nearest).
std::string downsample_fragment();

}  // namespace spume::shaders
