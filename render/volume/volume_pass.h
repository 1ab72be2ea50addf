#pragma once
// The absorption-only volume pass of Eq. 9 (MODEL.md §6): per pixel, the transmittance L of the
// diffuse material along the eye ray and its colour C_d; composite.h turns them into
// C_p = (1 - L) C_d + L C_b.
//
// Per eye ray (Camera::ray through the pixel centre, or jittered samples): the diffuse bounds (the
// box around every drawn sphere, a slab test: no BVH needed for one box) give [t_in, t_out];
// Embree's first hit on the opaque solids ends the ray earlier; the water surface is not opaque,
// its crossings (all recorded by an Embree filter) mark what is seen through water.
//   march: delta(x) at t_in + i dx for i = 0..floor((t_out - t_in) / dx), from per-type uniform
//          grids of the centres (point_grid.h); L = prod exp(-delta alpha dx).
//   exact: L = exp(-alpha * length of [t_in, t_out] inside the union of spheres), from each
//          chord computed exactly in double and a sweep over chords sorted by entry. Candidate
//          spheres come from screen-tile bins (screen_bins.h, default) or Embree's all-hits
//          filter (embree_scene.h); same chords, the bins are ~10x faster at 1M-15M spheres.
// With a shutter (motion blur) each particle's chord is averaged over its path instead, from bins of
// the paths (swept_trace.h). Colours: absorption.h. Bins of 2x2 tiles of 16x16 pixels run in parallel, each pixel written by one task
// and computed serially, so the image is the same bytes for any thread count.
#include <span>

#include "render/camera/camera.h"
#include "render/volume/volume_types.h"

namespace spume {

// True when some particle of a drawn type (radius > 0) exists; otherwise the pass is a no-op.
bool volume_pass_needed(DiffuseView frame, const VolumeSettings& settings);

// Throws Error for a bad setting (negative radius or alpha, no samples, ...) or frame arrays of
// different sizes. When nothing is drawn returns L = 1 everywhere without building anything.
// With settings.blurs() and the particles' velocities (m/s, one each), each particle's absorption is
// averaged over its path during the shutter (motion blur, swept_trace.h); the exact integrator only.
VolumeImage render_volume(DiffuseView frame, const Camera& camera, const VolumeSettings& settings,
                          const VolumeSurfaces& surfaces = {}, VolumeStats* stats = nullptr,
                          std::span<const Vec3f> velocities = {});

// The march step used for these settings (settings.march_step, or half the smallest drawn radius).
double march_step(const VolumeSettings& settings);

}  // namespace spume
