#pragma once
// Everything that talks to Embree 3 lives behind this header: one process-wide device whose error
// callback turns Embree errors into spume::Error, the surface scene (opaque solids + water surface)
// and the all-hits sphere scene. No Embree type leaks out.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "sim/core/frames.h"
#include "render/volume/volume_types.h"
#include "render/volume/water_path.h"

namespace spume {

// Opaque solids and the (not opaque) water surface in one scene. A ray's single trace gives the
// first opaque hit, and a filter on the water geometry records every water crossing and rejects it.
class SurfaceScene {
 public:
  explicit SurfaceScene(const VolumeSurfaces& surfaces);
  ~SurfaceScene();
  SurfaceScene(const SurfaceScene&) = delete;
  SurfaceScene& operator=(const SurfaceScene&) = delete;

  bool empty() const { return !impl_; }
  // Distance (m, along the unit direction d) to the first opaque hit before t_max, INFINITY when
  // none. Water crossings before it are appended to `crossings` with t relative to t_ref.
  double trace(const Vec3f& o, const Vec3f& d, double t_max, double t_ref, std::vector<WaterCrossing>& crossings) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Every drawn diffuse particle as an Embree sphere point (geomID = its type). collect() returns
// every (type, particle) whose sphere the ray segment touches, each once, in a fixed order.
class SphereHitScene {
 public:
  struct Hit {
    Vec3f centre;     // m, read from Embree's own vertex buffer (cache-warm after the trace)
    uint32_t type;    // DiffuseType (geomID)
  };
  SphereHitScene(DiffuseView frame, const std::array<float, kDiffuseTypeCount>& radius);
  ~SphereHitScene();
  SphereHitScene(const SphereHitScene&) = delete;
  SphereHitScene& operator=(const SphereHitScene&) = delete;

  size_t memory_bytes() const;  // vertex buffers only; the BVH is Embree's business
  // Events on [t_near, t_far] collected by a filter that records (geomID, primID) and rejects every
  // hit, sorted by that key and reduced to one entry per sphere: a sphere's entry and exit events
  // are paired by primID, never by order or normal sign (tangent and touching spheres give equal
  // t's). The caller recomputes each chord exactly; Embree's float t's are not used.
  void collect(const Vec3f& o, const Vec3f& d, float t_near, float t_far, std::vector<Hit>& spheres) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace spume
