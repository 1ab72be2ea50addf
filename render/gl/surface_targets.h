#pragma once
// The surface pass's render targets, kept from frame to frame and made again when the size changes.
// Full (supersampled) size:
//   opaque       sky, ground and solids (pass 1): colour, linear depth, depth-stencil
//   back_faces   the water's back faces (pass 2): depth only
//   front_faces  the water's front faces (pass 3): normal, linear depth (final_depth) over final_z
//   final_image  the shaded water over the opaque image (pass 4): final_colour over final_z, whose
//                stencil marks the water's pixels
// Output size, supersampling only: resolved (colour, depth, opaque depth, opaque colour), box-filtered
// (pass 5).
// Linear depths are m along the view axis, +inf where nothing was drawn.
#include "render/gl/gl_objects.h"

namespace spume {

struct SurfaceTargets {
  int width = 0, height = 0;  // the full size (pixels)
  GlTexture opaque_colour, opaque_depth, opaque_z, back_z, front_normal, final_colour, final_depth, final_z;
  GlFramebuffer opaque, back_faces, front_faces, final_image;
  int out_width = 0, out_height = 0;
  GlTexture resolved_colour, resolved_depth, resolved_opaque, resolved_opaque_colour;
  GlFramebuffer resolved;

  // Targets of w x h and, when the output's out_w x out_h differs, the resolved ones. Keeps whatever
  // already has its size: allocating and clearing the targets costs time on every first frame.
  void resize(int w, int h, int out_w, int out_h);

  // Binds `opaque` and clears it all: colour to black, linear depth to +inf, the depth buffer to the
  // far plane, the stencil to 0.
  void bind_and_clear_opaque() const;
  // Binds `back_faces` and clears its depth buffer to the far plane.
  void bind_and_clear_back_faces() const;
  // The opaque colour, linear depth and depth-stencil into the final targets, which the water then
  // draws over.
  void copy_opaque_to_final() const;
};

}  // namespace spume
