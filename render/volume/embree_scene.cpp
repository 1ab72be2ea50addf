#include "render/volume/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "render/surface/triangle_mesh.h"
#include "render/volume/quad_pairs.h"

namespace spume {
namespace {

// Embree reports errors through a callback that may run on its worker threads; keep the first
// message and raise it as an Error from the calling thread after each build.
struct DeviceErrors {
  std::mutex mutex;
  std::string first;
};

void on_embree_error(void* user, RTCError code, const char* message) {
  auto* errors = static_cast<DeviceErrors*>(user);
  std::lock_guard<std::mutex> lock(errors->mutex);
  if (errors->first.empty()) errors->first = str("Embree error ", int(code), ": ", message ? message : "(no message)");
}

struct Device {
  RTCDevice device = nullptr;
  DeviceErrors errors;
  Device() {
    device = rtcNewDevice(nullptr);
    if (!device) fail("Embree: cannot create a device (error ", int(rtcGetDeviceError(nullptr)), ")");
    rtcSetDeviceErrorFunction(device, on_embree_error, &errors);
  }
  // Process lifetime: Embree devices are heavy and thread-safe; released at exit by the OS.
};

Device& device() {
  static Device d;
  return d;
}

void check(const char* what) {
  Device& d = device();
  std::lock_guard<std::mutex> lock(d.errors.mutex);
  if (!d.errors.first.empty()) {
    std::string message = std::move(d.errors.first);
    d.errors.first.clear();
    fail(what, ": ", message);
  }
}

// A context carrying per-ray storage to the filters. rtcIntersect1 traces one ray per context, so
// every valid lane a filter sees (whatever its packet width N) belongs to this ray.
template <typename Hits>
struct FilterContext {
  RTCIntersectContext base;  // first member: Embree passes &base back to the filter
  Hits* hits;
};

struct RawHit {
  float t;
  uint32_t geom, prim;
};

// Records every hit and rejects it, so traversal goes on and tfar never shrinks.
void record_and_reject(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<FilterContext<std::vector<RawHit>>*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    ctx->hits->push_back({RTCRayN_tfar(args->ray, args->N, i), RTCHitN_geomID(args->hit, args->N, i),
                          RTCHitN_primID(args->hit, args->N, i)});
    args->valid[i] = 0;
  }
}

// The same for the sphere scene, where only the sphere's identity matters: key geomID:primID.
void record_key_and_reject(const RTCFilterFunctionNArguments* args) {
  auto* ctx = reinterpret_cast<FilterContext<std::vector<uint64_t>>*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    ctx->hits->push_back(uint64_t(RTCHitN_geomID(args->hit, args->N, i)) << 32 | RTCHitN_primID(args->hit, args->N, i));
    args->valid[i] = 0;
  }
}

RTCRayHit make_ray(const Vec3f& o, const Vec3f& d, float t_near, float t_far) {
  RTCRayHit rh{};
  rh.ray.org_x = o.x(), rh.ray.org_y = o.y(), rh.ray.org_z = o.z();
  rh.ray.dir_x = d.x(), rh.ray.dir_y = d.y(), rh.ray.dir_z = d.z();
  rh.ray.tnear = t_near, rh.ray.tfar = t_far;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

// A geometry of `type` over the mesh's vertices, with `primitives` of `corners` vertex indices each
// copied from `index`; returns Embree's copy of the vertices (x, y, z a vertex), which the geometry owns.
const float* new_mesh_geometry(RTCGeometry g, const TriangleMesh& mesh, const uint32_t* index, size_t primitives,
                               int corners) {
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  auto* p = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, corners == 4 ? RTC_FORMAT_UINT4 : RTC_FORMAT_UINT3,
                                                           size_t(corners) * sizeof(uint32_t), primitives));
  check("Embree mesh buffers");
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int c = 0; c < 3; ++c) v[3 * i + size_t(c)] = mesh.vertices[i][c];
  std::copy(index, index + size_t(corners) * primitives, p);
  return v;
}

RTCGeometry triangle_geometry(const TriangleMesh& mesh) {
  RTCGeometry g = rtcNewGeometry(device().device, RTC_GEOMETRY_TYPE_TRIANGLE);
  new_mesh_geometry(g, mesh, mesh.indices.data(), mesh.triangle_count(), 3);
  return g;
}

// The mesh's vertices with the quads' corners; *vertices is set to Embree's copy of them.
RTCGeometry quad_geometry(const TriangleMesh& mesh, const QuadPairs& quads, const float** vertices) {
  RTCGeometry g = rtcNewGeometry(device().device, RTC_GEOMETRY_TYPE_QUAD);
  *vertices = new_mesh_geometry(g, mesh, quads.corners.data(), quads.size(), 4);
  return g;
}

bool has_triangles(const TriangleMesh* m) { return m && m->triangle_count() > 0; }

void validate_mesh(const TriangleMesh& m, const char* name) {
  if (m.indices.size() % 3) fail("volume pass: ", name, " mesh has ", m.indices.size(), " indices, not a multiple of 3");
  for (uint32_t i : m.indices)
    if (i >= m.vertices.size()) fail("volume pass: ", name, " mesh index ", i, " >= vertex count ", m.vertices.size());
}

}  // namespace

struct SurfaceScene::Impl {
  RTCScene scene = nullptr;
  unsigned water_geom = RTC_INVALID_GEOMETRY_ID;
  QuadPairs water;                  // Embree's primitives are these quads (their corners: Embree's copy)
  std::vector<Vec3f> water_normal;  // per triangle, outward for counter-clockwise triangles
  const float* water_vertices = nullptr;  // Embree's vertex buffer (x, y, z a vertex)
  const uint32_t* water_corners = nullptr;  // Embree's index buffer (4 corners a quad)
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
  }
  // The triangle of quad q that a hit at point p lies on: the half whose plane is nearer. Both planes
  // hold the shared diagonal, and a point of one half lies near the other's plane only near that
  // diagonal, where either half is a true answer.
  uint32_t water_triangle(uint32_t q, const Vec3d& p) const;
};

uint32_t SurfaceScene::Impl::water_triangle(uint32_t q, const Vec3d& p) const {
  if (!water.paired(q)) return water.first[q];
  const uint32_t v1 = water_corners[4 * size_t(q) + 1];
  const Vec3d on_both = Vec3d(water_vertices[3 * size_t(v1)], water_vertices[3 * size_t(v1) + 1], water_vertices[3 * size_t(v1) + 2]);
  auto distance = [&](uint32_t t) {
    const Vec3d n = water_normal[t].cast<double>();
    const double length = n.norm();
    return length > 0.0 ? std::abs(n.dot(p - on_both)) / length : INFINITY;
  };
  const uint32_t a = water.first[q], b = water.second[q];
  return distance(b) < distance(a) ? b : a;
}

SurfaceScene::SurfaceScene(const VolumeSurfaces& s) {
  const bool water = has_triangles(s.water), solids = has_triangles(s.solids);
  if (!water && !solids) return;
  impl_ = std::make_unique<Impl>();
  // ROBUST: no watertightness shortcuts, so a ray through a shared edge is not lost between triangles.
  impl_->scene = rtcNewScene(device().device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  if (solids) {
    validate_mesh(*s.solids, "solids");
    RTCGeometry g = triangle_geometry(*s.solids);
    rtcCommitGeometry(g);
    rtcAttachGeometry(impl_->scene, g);
    rtcReleaseGeometry(g);
  }
  if (water) {
    validate_mesh(*s.water, "water surface");
    impl_->water = pair_triangles(*s.water);
    RTCGeometry g = quad_geometry(*s.water, impl_->water, &impl_->water_vertices);
    impl_->water_corners = static_cast<const uint32_t*>(rtcGetGeometryBufferData(g, RTC_BUFFER_TYPE_INDEX, 0));
    std::vector<uint32_t>().swap(impl_->water.corners);  // 16 bytes a quad that Embree holds too
    rtcSetGeometryIntersectFilterFunction(g, record_and_reject);
    rtcCommitGeometry(g);
    impl_->water_geom = rtcAttachGeometry(impl_->scene, g);
    rtcReleaseGeometry(g);
    const TriangleMesh& m = *s.water;
    impl_->water_normal.resize(m.triangle_count());
    for (size_t t = 0; t < m.triangle_count(); ++t) {
      const Vec3f &a = m.vertices[m.indices[3 * t]], &b = m.vertices[m.indices[3 * t + 1]], &c = m.vertices[m.indices[3 * t + 2]];
      impl_->water_normal[t] = (b - a).cross(c - a);
    }
  }
  rtcCommitScene(impl_->scene);
  check("building the Embree surface scene");
}

SurfaceScene::~SurfaceScene() = default;

double SurfaceScene::trace(const Vec3f& o, const Vec3f& d, double t_max, double t_ref, std::vector<WaterCrossing>& crossings) const {
  if (!impl_) return INFINITY;
  thread_local std::vector<RawHit> water_hits;
  water_hits.clear();
  FilterContext<std::vector<RawHit>> ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.hits = &water_hits;
  // Nothing beyond the diffuse bounds matters; a hair longer so float rounding cannot cut it short.
  RTCRayHit rh = make_ray(o, d, 0.0f, std::isfinite(t_max) ? float(t_max * (1.0 + 1e-6) + 1e-6) : INFINITY);
  rtcIntersect1(impl_->scene, &ctx.base, &rh);
  const double t_hit = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? INFINITY : double(rh.ray.tfar);
  // Hits recorded before traversal found the closest opaque hit may lie beyond it.
  for (const RawHit& h : water_hits)
    if (double(h.t) < t_hit) {
      const Vec3d p = o.cast<double>() + double(h.t) * d.cast<double>();
      const uint32_t triangle = impl_->water_triangle(h.prim, p);
      crossings.push_back({double(h.t) - t_ref, impl_->water_normal[triangle].dot(d) < 0.0f});
    }
  return t_hit;
}

struct SphereHitScene::Impl {
  RTCScene scene = nullptr;
  std::array<const float*, kDiffuseTypeCount> xyzr{};  // Embree's vertex buffers, per type
  size_t bytes = 0;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
  }
};

SphereHitScene::SphereHitScene(DiffuseView frame, const std::array<float, kDiffuseTypeCount>& radius)
    : impl_(std::make_unique<Impl>()) {
  impl_->scene = rtcNewScene(device().device);
  std::array<std::vector<uint32_t>, kDiffuseTypeCount> particle;  // primID -> particle index, per type
  for (size_t i = 0; i < frame.size(); ++i) {
    const size_t k = size_t(frame.types[i]);
    if (radius[k] > 0.0f) particle[k].push_back(uint32_t(i));
  }
  for (unsigned k = 0; k < unsigned(kDiffuseTypeCount); ++k) {
    const std::vector<uint32_t>& idx = particle[k];
    if (idx.empty()) continue;
    RTCGeometry g = rtcNewGeometry(device().device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* xyzr = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), idx.size()));
    check("Embree sphere buffer");
    parallel_for(idx.size(), 1 << 16, [&](size_t b, size_t e) {
      for (size_t j = b; j < e; ++j) {
        const Vec3f& p = frame.positions[idx[j]];
        xyzr[4 * j] = p.x(), xyzr[4 * j + 1] = p.y(), xyzr[4 * j + 2] = p.z(), xyzr[4 * j + 3] = radius[k];
      }
    });
    impl_->xyzr[k] = xyzr;
    rtcSetGeometryIntersectFilterFunction(g, record_key_and_reject);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(impl_->scene, g, k);
    rtcReleaseGeometry(g);  // the scene keeps it (and its buffer) alive
    impl_->bytes += idx.size() * 16;
  }
  rtcCommitScene(impl_->scene);
  check("building the Embree sphere scene");
}

SphereHitScene::~SphereHitScene() = default;

size_t SphereHitScene::memory_bytes() const { return impl_->bytes; }

void SphereHitScene::collect(const Vec3f& o, const Vec3f& d, float t_near, float t_far, std::vector<Hit>& spheres) const {
  thread_local std::vector<uint64_t> keys;
  keys.clear();
  FilterContext<std::vector<uint64_t>> ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.hits = &keys;
  RTCRayHit rh = make_ray(o, d, t_near, t_far);
  rtcIntersect1(impl_->scene, &ctx.base, &rh);
  // Hits arrive in BVH order; sorting the keys puts each sphere's events side by side.
  std::sort(keys.begin(), keys.end());
  spheres.clear();
  for (size_t i = 0; i < keys.size(); ++i) {
    if (i > 0 && keys[i] == keys[i - 1]) continue;
    const uint32_t type = uint32_t(keys[i] >> 32);
    const float* p = impl_->xyzr[type] + 4 * size_t(uint32_t(keys[i]));
    spheres.push_back({Vec3f(p[0], p[1], p[2]), type});
  }
}

}  // namespace spume
