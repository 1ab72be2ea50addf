#pragma once
// The surface pass's GL side (surface_pass.h): the state kept from frame to frame and the pass's
// steps, in the order SurfacePass::render_gl calls them; each leaves the GL state the next expects.
// Included by surface_pass.cpp and surface_gpu.cpp only.
#include <memory>
#include <vector>

#include "render/gl/gl_objects.h"
#include "render/gl/sun_shadow.h"
#include "render/gl/surface_pass.h"
#include "render/gl/surface_targets.h"
#include "render/gl/surface_view.h"

namespace spume {

// Where the read-back finds the four outputs: a framebuffer and colour attachment each (the colour
// is attachment 0).
struct SurfaceOutputs {
  GLuint colour_fb, depth_fb, opaque_fb, opaque_colour_fb;
  GLenum depth_attachment, opaque_attachment, opaque_colour_attachment;
};

struct SurfacePass::Gpu {
  OsmesaContext context;
  GlProgram sky, solid, ground, back, water_normal, water;
  std::unique_ptr<GlProgram> downsample;  // compiled on the first supersampled frame
  GLuint empty_vao = 0, env_ubo = 0, frame_ubo = 0;
  GpuMesh fluid, ground_quad;
  SunShadow shadow;
  std::vector<std::unique_ptr<GpuMesh>> solids, slabs;  // slabs: the walls' shadow casters
  SurfaceTargets targets;

  explicit Gpu(const OsmesaOptions& options);  // creates the context and compiles the programs
  ~Gpu();

  // The solids (and the slabs that cast the shadows of walls) to the GPU, into buffers kept per solid
  // from frame to frame; adds their triangles and returns what casts the sun's shadow.
  std::vector<SunShadow::Caster> upload_solids(const std::vector<SceneSolid>& scene_solids, size_t& triangles);
  void upload_fluid(const SurfaceScene& scene, size_t& triangles);

  // What every later pass reads: the Env and Frame blocks and the shadow map (unit 3); and the state
  // the shadow map changed, the viewport, back to the frame's. The projection is upside down, which
  // makes the front faces clockwise.
  void set_frame_inputs(const SurfaceScene& scene, const SurfaceView& view, bool shadows);

  // Pass 1: solids, then the ground, then the sky where nothing was drawn (on the far plane): front to
  // back, so the depth test rejects hidden fragments before they are shaded.
  void draw_opaque(const SurfaceScene& scene, const Vec3f& eye);
  void draw_solids(const std::vector<SceneSolid>& scene_solids);
  // A quad centred under the eye, large enough that the haze hides its edge; none seen from below.
  void draw_ground(const Environment& e, const Vec3f& eye);
  // A full-screen triangle on the far plane: passes the depth test (LEQUAL) only where nothing was
  // drawn, and leaves the depth buffer as it is.
  void draw_sky();
  void draw_full_screen() const;  // the full-screen triangle, from the vertex index alone

  // Pass 2: the nearest back faces: where view rays leave the water (the path they travel in it).
  void draw_water_back_faces();
  // Pass 3: the front faces' normals and depths over copies of the opaque image and depths (solids in
  // front still hide the water); the stencil marks the pixels they cover.
  void draw_water_front_faces();
  // Pass 4: shades each pixel the stencil marks, once (the stencil test runs before the shader, so a
  // full-screen triangle costs only the water's pixels), over the copy of the opaque image.
  void shade_water();

  // Without supersampling the outputs are read from the targets as drawn: the image with the water
  // when there is water, else the opaque one.
  SurfaceOutputs full_size_outputs(bool with_water) const;
  // Pass 5, supersampling only: box-filters the colour and takes the nearest depths into the resolved
  // targets of the output size (out_w x out_h), so that only the output's pixels are read back.
  SurfaceOutputs downsample_outputs(bool with_water, int supersample, int out_w, int out_h);
  // Reads the float targets back as they are, straight into the image's arrays (llvmpipe copies
  // them; about 5 ms at 1920x1080).
  // The opaque image (pass 1) only when opaque_colour is asked for.
  static SurfaceImage read_back(const SurfaceOutputs& from, int w, int h, bool opaque_colour);
};

}  // namespace spume
