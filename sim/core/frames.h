#pragma once
// The plain data that flows between stages: fluid frames in, diffuse frames out. Parallel arrays plus
// metadata, with size checks only; the algorithms live elsewhere.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sim/keys/scene_keys.h"
#include "sim/core/vec.h"

namespace spume {

// One frame of a particle fluid, as read from a cache or produced by the solver.
struct FluidFrame {
  int index = 0;                  // frame number in the sequence
  double time = 0.0;              // s
  std::vector<Vec3f> positions;   // m
  std::vector<Vec3f> velocities;  // m/s; empty when the source had none (then frame differences are used)
  std::vector<uint32_t> ids;      // stable particle ids; empty when the source had none (index order)
  std::vector<float> masses;      // kg; empty for uniform mass

  size_t size() const { return positions.size(); }
  bool has_velocities() const { return !velocities.empty(); }
  bool has_ids() const { return !ids.empty(); }
  uint32_t id(size_t i) const { return ids.empty() ? uint32_t(i) : ids[i]; }

  // Throws Error naming `where` when array sizes disagree, a value is NaN/Inf, or ids repeat.
  void validate(const std::string& where) const;
};

// What a fluid sequence is, beyond its frames.
struct FluidSequenceInfo {
  float particle_radius = 0.0f;  // m; the fluid particle's volume radius r (spacing 2r)
  float support_radius = 0.0f;   // m; the influence radius h
  double fps = keys::fluid::fps.value[0];                        // frames per second
  float rest_density = float(keys::fluid::rest_density.value[0]);  // kg/m^3; uniform mass rho0 (2r)^3
  float uniform_mass() const { return rest_density * 8.0f * particle_radius * particle_radius * particle_radius; }
};

enum class DiffuseType : uint8_t { Spray = 0, Foam = 1, Bubble = 2 };
constexpr int kDiffuseTypeCount = 3;
const char* to_string(DiffuseType t);

// Diffuse material at one frame. Ids are stable across frames (MODEL.md §2: parent fluid id, birth
// step, sample index), see diffuse_id().
struct DiffuseFrame {
  int index = 0;
  double time = 0.0;               // s
  std::vector<uint64_t> ids;
  std::vector<Vec3f> positions;    // m
  std::vector<Vec3f> velocities;   // m/s
  std::vector<float> lifetimes;    // s remaining
  std::vector<DiffuseType> types;

  size_t size() const { return positions.size(); }
  void resize(size_t n);
  void reserve(size_t n);
  std::array<size_t, kDiffuseTypeCount> count_by_type() const;  // an invalid type (>= 3) is not counted
  void validate(const std::string& where) const;
};

// What a renderer draws of a diffuse frame: where each particle is and what it is. Reading only these
// from a cache (io/spume_cache.h, read_diffuse_points) skips the ids, velocities and lifetimes, most of
// a compact cache's bytes.
struct DiffusePoints {
  int index = 0;
  double time = 0.0;               // s
  std::vector<Vec3f> positions;    // m
  std::vector<DiffuseType> types;

  size_t size() const { return positions.size(); }
};

// Positions and types of either, without a copy; valid while the frame it views lives.
struct DiffuseView {
  int index = 0;
  std::span<const Vec3f> positions;
  std::span<const DiffuseType> types;

  DiffuseView(const DiffuseFrame& f) : index(f.index), positions(f.positions), types(f.types) {}
  DiffuseView(const DiffusePoints& p) : index(p.index), positions(p.positions), types(p.types) {}
  size_t size() const { return positions.size(); }
  std::array<size_t, kDiffuseTypeCount> count_by_type() const;  // an invalid type (>= 3) is not counted
};

// Particles of each type among `types`; an invalid type (>= 3) is not counted.
std::array<size_t, kDiffuseTypeCount> count_types(std::span<const DiffuseType> types);

// A diffuse particle's id: parent fluid id (32 bits), global birth step (20 bits), sample (12 bits).
constexpr uint32_t kMaxBirthStep = (1u << 20) - 1;
constexpr uint32_t kMaxSamplesPerStep = (1u << 12) - 1;
inline uint64_t diffuse_id(uint32_t parent, uint32_t step, uint32_t sample) {
  return (uint64_t(parent) << 32) | (uint64_t(step & kMaxBirthStep) << 12) | (sample & kMaxSamplesPerStep);
}
inline uint32_t diffuse_id_parent(uint64_t id) { return uint32_t(id >> 32); }
inline uint32_t diffuse_id_step(uint64_t id) { return uint32_t(id >> 12) & kMaxBirthStep; }
inline uint32_t diffuse_id_sample(uint64_t id) { return uint32_t(id) & kMaxSamplesPerStep; }

}  // namespace spume
