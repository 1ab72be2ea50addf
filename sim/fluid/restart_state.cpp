#include "sim/fluid/restart_state.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <ostream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/crc_file.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

static_assert(std::endian::native == std::endian::little, "restart files are written straight from memory");
static_assert(sizeof(Vec3f) == 12, "Vec3f must be three packed floats");

constexpr char kMagic[] = "SPUMERS1";
constexpr size_t kHeaderSize = 184;
constexpr size_t kDigestSize = 16;
constexpr uint32_t kHasWarmStart = 1u;

std::string header_of(const FluidRestartState& s) {
  using io::Endian;
  std::string h(kMagic, 8);
  io::store(h, kRestartVersion, Endian::Little);
  io::store(h, s.frame, Endian::Little);
  io::store(h, s.time, Endian::Little);
  io::store(h, s.dt_prev, Endian::Little);
  io::store(h, s.particle_radius, Endian::Little);
  io::store(h, s.density_warm.empty() ? 0u : kHasWarmStart, Endian::Little);
  io::store(h, uint64_t(s.size()), Endian::Little);
  std::string digest = s.digest.substr(0, kDigestSize);
  digest.resize(kDigestSize, '\0');
  h += digest;
  const SolverCounters& c = s.counters;
  for (uint64_t count : {c.steps, c.density_iterations, c.divergence_iterations, c.density_unconverged,
                         c.divergence_unconverged, c.corrections, c.dt_clamped_to_min, c.retries})
    io::store(h, count, Endian::Little);
  for (double d : {c.dt_sum, c.density_error, c.max_density_error, c.divergence_error, c.min_dt_used, c.max_dt_used,
                   c.step_cap})
    io::store(h, d, Endian::Little);
  return h;
}

constexpr size_t kBodyBytes = 56;

std::string body_section(const std::vector<BodyPose>& bodies) {
  using io::Endian;
  std::string b;
  io::store(b, uint32_t(bodies.size()), Endian::Little);
  for (const BodyPose& p : bodies) {
    io::store(b, p.solid, Endian::Little);
    const Quatf& q = p.orientation;
    for (float f : {p.position.x(), p.position.y(), p.position.z(), q.w(), q.x(), q.y(), q.z(), p.velocity.x(),
                    p.velocity.y(), p.velocity.z(), p.angular_velocity.x(), p.angular_velocity.y(),
                    p.angular_velocity.z()})
      io::store(b, f, Endian::Little);
  }
  return b;
}

std::vector<BodyPose> read_bodies(io::ByteReader& r, const std::string& where) {
  const uint32_t m = r.read<uint32_t>("body count");
  if (m != r.remaining() / kBodyBytes || m * kBodyBytes != r.remaining())
    fail(where, ": ", m, " bodies do not fit the ", r.remaining(), " bytes after the particles (truncated or corrupt)");
  std::vector<BodyPose> bodies(m);
  for (BodyPose& p : bodies) {
    p.solid = r.read<uint32_t>("body solid");
    float f[13];
    for (float& x : f) x = r.read<float>("body pose");
    for (float x : f)
      if (!std::isfinite(x)) fail(where, ": body of solid ", p.solid, " has a non-finite pose or velocity");
    p.position = Vec3f(f[0], f[1], f[2]);
    p.orientation = Quatf(f[3], f[4], f[5], f[6]);
    p.velocity = Vec3f(f[7], f[8], f[9]);
    p.angular_velocity = Vec3f(f[10], f[11], f[12]);
  }
  return bodies;
}

template <typename T>
void read_array(io::ByteReader& r, std::vector<T>& out, size_t n, const char* what) {
  r.require_array(n, sizeof(T), what);
  out.resize(n);
  if (n) std::memcpy(static_cast<void*>(out.data()), r.take(n * sizeof(T), what).data(), n * sizeof(T));
}

}  // namespace

void write_restart_state(const std::filesystem::path& path, const FluidRestartState& s) {
  const size_t n = s.size();
  if (s.positions.size() != n || s.velocities.size() != n ||
      (!s.density_warm.empty() && (s.density_warm.size() != n || s.divergence_warm.size() != n)))
    fail(path.string(), ": restart state arrays of unequal length");
  const std::string header = header_of(s);
  write_crc_file(path, header, s.ids, s.positions, s.velocities, s.density_warm, s.divergence_warm,
                 body_section(s.bodies));
}

FluidRestartState read_restart_state(const std::filesystem::path& path) {
  const std::string where = path.string();
  const std::string bytes = io::read_file_bytes(path);
  if (bytes.size() < kHeaderSize + 4 || bytes.compare(0, 8, kMagic) != 0)
    fail(where, ": not a spume restart file (magic '", kMagic, "' and a ", kHeaderSize, "-byte header expected)");
  const uint32_t stored = io::load<uint32_t>(bytes.data() + bytes.size() - 4, io::Endian::Little);
  const uint32_t computed = crc32_update(crc32_start(), bytes.data(), bytes.size() - 4);
  if (stored != computed) fail(where, ": corrupt: CRC-32 mismatch (stored ", stored, ", computed ", computed, ")");

  io::ByteReader r(std::string_view(bytes).substr(0, bytes.size() - 4), where);
  r.skip(8, "magic");
  FluidRestartState s;
  const uint32_t version = r.read<uint32_t>("version");
  if (version != kRestartVersion && version != 2)
    fail(where, ": restart file version ", version, "; this build reads 2 and ", kRestartVersion);
  s.frame = r.read<int32_t>("frame");
  s.time = r.read<double>("time");
  s.dt_prev = r.read<double>("dt_prev");
  s.particle_radius = r.read<float>("particle radius");
  const uint32_t flags = r.read<uint32_t>("flags");
  if (flags & ~kHasWarmStart) fail(where, ": restart flags ", flags, "; only bit 0 (warm-start arrays) is known");
  const uint64_t n = r.read<uint64_t>("count");
  const std::string_view digest = r.take(kDigestSize, "digest");
  s.digest = std::string(digest.substr(0, digest.find('\0')));
  SolverCounters& c = s.counters;
  for (uint64_t* count : {&c.steps, &c.density_iterations, &c.divergence_iterations, &c.density_unconverged,
                          &c.divergence_unconverged, &c.corrections, &c.dt_clamped_to_min, &c.retries})
    *count = r.read<uint64_t>("counters");
  for (double* d : {&c.dt_sum, &c.density_error, &c.max_density_error, &c.divergence_error, &c.min_dt_used,
                    &c.max_dt_used, &c.step_cap})
    *d = r.read<double>("statistics");
  const uint64_t per_particle = 4 + 12 + 12 + (flags & kHasWarmStart ? 8 : 0);
  const uint64_t bodies_at_least = version >= 3 ? 4 : 0;  // the body count
  const uint64_t for_particles = r.remaining() >= bodies_at_least ? r.remaining() - bodies_at_least : 0;
  if (n > for_particles / per_particle || (version < 3 && n * per_particle != r.remaining()))
    fail(where, ": ", n, " particles do not fit the file size ", bytes.size(), " bytes (truncated or corrupt)");
  read_array(r, s.ids, n, "ids");
  read_array(r, s.positions, n, "positions");
  read_array(r, s.velocities, n, "velocities");
  if (flags & kHasWarmStart) {
    read_array(r, s.density_warm, n, "density warm start");
    read_array(r, s.divergence_warm, n, "divergence warm start");
  }
  if (version >= 3) s.bodies = read_bodies(r, where);
  if (!std::isfinite(s.time) || !std::isfinite(s.dt_prev) || !(s.dt_prev > 0.0) ||
      !std::isfinite(s.particle_radius) || !std::isfinite(c.step_cap) || !(c.step_cap > 0.0))
    fail(where, ": time ", s.time, ", dt_prev ", s.dt_prev, ", step cap ", c.step_cap, " and radius ",
         s.particle_radius, " must be finite (dt_prev and the step cap > 0)");
  for (size_t i = 0; i < n; ++i)
    if (!finite(s.positions[i]) || !finite(s.velocities[i]))
      fail(where, ": particle ", s.ids[i], " has a non-finite position or velocity");
  return s;
}

}  // namespace spume
