#include "sim/io/fluid_survey.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/progress.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/particle_file.h"
#include "sim/io/stage_record.h"

namespace spume {
namespace {

using Json = nlohmann::json;

constexpr int kSurveyVersion = 6;  // bump when what a frame's entry holds changes

// An entry's digest covers its file identity and what was measured in it: an entry edited by hand
// (or by a tool that kept the file's identity) no longer matches and its frame is surveyed again.
std::string entry_digest(Json entry) {
  entry.erase("digest");
  return record_digest(entry);
}

Json to_json(const FrameSurvey& f) {
  Json j = {{"frame", f.frame},
            {"size", f.file.size},
            {"mtime_ns", f.file.mtime_ns},
            {"crc", f.file.crc},
            {"particles", f.particles}};
  // An empty frame has no bounds and no sheets (its box is inverted: infinities, not JSON numbers).
  if (f.particles > 0) {
    j["min"] = {f.bounds.min.x(), f.bounds.min.y(), f.bounds.min.z()};
    j["max"] = {f.bounds.max.x(), f.bounds.max.y(), f.bounds.max.z()};
    j["sheet"] = f.sheet;
    j["centroid"] = {f.centroid.x(), f.centroid.y(), f.centroid.z()};
    if (f.has_mean_velocity()) {
      j["mean_velocity"] = {f.mean_velocity.x(), f.mean_velocity.y(), f.mean_velocity.z()};
      j["column"] = f.column;
      Json fronts = Json::array();
      for (const FrameSurvey::ColumnFront& c : f.fronts) fronts.push_back({c.side, c.i, c.j, c.sheet, c.velocity});
      j["fronts"] = fronts;
      Json tracked = Json::array();
      for (const FrameSurvey::Tracked& t : f.tracked)
        tracked.push_back({t.id, t.position.x(), t.position.y(), t.position.z(), t.velocity.x(), t.velocity.y(),
                           t.velocity.z()});
      j["tracked"] = tracked;
    }
  }
  j["digest"] = entry_digest(j);
  return j;
}

// Throws when the entry is malformed or does not match its digest.
FrameSurvey frame_from_json(const Json& j) {
  if (j.at("digest").get<std::string>() != entry_digest(j)) throw std::runtime_error("digest");
  FrameSurvey f;
  f.frame = j.at("frame").get<int>();
  f.file.size = j.at("size").get<uint64_t>();
  f.file.mtime_ns = j.at("mtime_ns").get<int64_t>();
  f.file.crc = j.at("crc").get<uint32_t>();
  f.particles = j.at("particles").get<uint64_t>();
  if (f.particles > 0) {
    for (int a = 0; a < 3; ++a) f.bounds.min[a] = j.at("min").at(size_t(a)).get<float>();
    for (int a = 0; a < 3; ++a) f.bounds.max[a] = j.at("max").at(size_t(a)).get<float>();
    f.sheet = j.at("sheet").get<std::array<float, 6>>();
    for (int a = 0; a < 3; ++a) f.centroid[a] = j.at("centroid").at(size_t(a)).get<float>();
    if (j.contains("mean_velocity")) {
      for (int a = 0; a < 3; ++a) f.mean_velocity[a] = j.at("mean_velocity").at(size_t(a)).get<float>();
      f.column = j.at("column").get<float>();
      for (const Json& c : j.at("fronts"))
        f.fronts.push_back({c.at(0).get<int>(), c.at(1).get<int>(), c.at(2).get<int>(), c.at(3).get<float>(),
                            c.at(4).get<float>()});
      for (const Json& t : j.at("tracked"))
        f.tracked.push_back({t.at(0).get<uint32_t>(),
                             Vec3f(t.at(1).get<float>(), t.at(2).get<float>(), t.at(3).get<float>()),
                             Vec3f(t.at(4).get<float>(), t.at(5).get<float>(), t.at(6).get<float>())});
    }
  } else {
    f.sheet.fill(NAN);
    f.centroid = Vec3f::Constant(NAN);
  }
  return f;
}

Json spacing_json(const std::string& pattern, float spacing, int frame, const FileIdentity& file) {
  Json j = {{"pattern", pattern},
            {"spacing", spacing},
            {"spacing_frame", frame},
            {"spacing_size", file.size},
            {"spacing_mtime_ns", file.mtime_ns},
            {"spacing_crc", file.crc}};
  j["spacing_digest"] = record_digest(j);
  return j;
}

// What an earlier survey of the same pattern and layer recorded, by frame; nothing when the file is
// missing, unreadable or of another pattern (it is only a shortcut: surveying again is always right).
struct Kept {
  std::vector<FrameSurvey> frames;
  float spacing = 0.0f;
  int spacing_frame = -1;
  FileIdentity spacing_file;
  size_t rejected = 0;  // entries that were malformed or did not match their digest
};

Kept read_kept(const std::filesystem::path& keep, const std::string& pattern) {
  Kept kept;
  if (keep.empty()) return kept;
  std::ifstream in(keep);
  if (!in) return kept;
  try {
    const Json j = Json::parse(in);
    if (j.at("pattern").get<std::string>() != pattern || j.at("version").get<int>() != kSurveyVersion) return kept;
    for (const Json& f : j.at("frames")) {
      try {
        kept.frames.push_back(frame_from_json(f));
      } catch (const std::exception&) {
        ++kept.rejected;  // this frame is surveyed again; the others stay good
      }
    }
    const int spacing_frame = j.at("spacing_frame").get<int>();
    const FileIdentity spacing_file{j.at("spacing_size").get<uint64_t>(), j.at("spacing_mtime_ns").get<int64_t>(),
                                    j.at("spacing_crc").get<uint32_t>()};
    const float spacing = j.at("spacing").get<float>();
    if (spacing_json(pattern, spacing, spacing_frame, spacing_file)["spacing_digest"] == j.at("spacing_digest")) {
      kept.spacing = spacing;
      kept.spacing_frame = spacing_frame;
      kept.spacing_file = spacing_file;
    } else {
      ++kept.rejected;
    }
  } catch (const std::exception&) {
    return Kept{};
  }
  return kept;
}

}  // namespace

Aabb FluidSurvey::bounds() const {
  Aabb box;
  for (const FrameSurvey& f : frames) box.extend(f.bounds);
  return box;
}

namespace {

// The columns' extremes of one frame (FrameSurvey::fronts), on columns of side `column`.
std::vector<FrameSurvey::ColumnFront> column_fronts(const std::vector<Vec3f>& positions,
                                                   const std::vector<Vec3f>& velocities, const Aabb& bounds,
                                                   float column) {
  constexpr size_t kSheetRank = 4, kVelocityRank = 8;
  struct Outer {
    float key = INFINITY;  // more outward is smaller: the high sides negated
    uint32_t index = UINT32_MAX;
  };
  std::vector<FrameSurvey::ColumnFront> fronts;
  for (int side = 2; side <= 3; ++side) {  // -y and +y
    const int axis = side / 2, u = axis == 0 ? 1 : 0, w = axis == 2 ? 1 : 2;
    const int u0 = int(std::floor(bounds.min[u] / column)), w0 = int(std::floor(bounds.min[w] / column));
    const int nu = int(std::floor(bounds.max[u] / column)) - u0 + 1, nw = int(std::floor(bounds.max[w] / column)) - w0 + 1;
    std::vector<std::array<Outer, kVelocityRank>> outer(size_t(nu) * size_t(nw));
    std::vector<uint32_t> held(outer.size(), 0);
    for (size_t i = 0; i < positions.size(); ++i) {
      const Vec3f& p = positions[i];
      const int cu = std::clamp(int(std::floor(p[u] / column)) - u0, 0, nu - 1);
      const int cw = std::clamp(int(std::floor(p[w] / column)) - w0, 0, nw - 1);
      const size_t c = size_t(cu) * size_t(nw) + size_t(cw);
      ++held[c];
      const float key = side % 2 == 0 ? p[axis] : -p[axis];
      auto& o = outer[c];
      if (!(key < o[kVelocityRank - 1].key)) continue;
      size_t k = kVelocityRank - 1;
      while (k > 0 && key < o[k - 1].key) o[k] = o[k - 1], --k;
      o[k] = Outer{key, uint32_t(i)};
    }
    for (size_t c = 0; c < outer.size(); ++c) {
      if (held[c] < kSheetRank) continue;
      const size_t n = std::min<size_t>(held[c], kVelocityRank);
      double along = 0.0;
      for (size_t k = 0; k < n; ++k) along += double(velocities[outer[c][k].index][axis]);
      const float key = outer[c][kSheetRank - 1].key;
      fronts.push_back({side, int(c / size_t(nw)) + u0, int(c % size_t(nw)) + w0, side % 2 == 0 ? key : -key,
                        float(along / double(n))});
    }
  }
  return fronts;
}

// The particles tracked from frame to frame (FrameSurvey::tracked): the lowest ids under a fixed mixing
// hash, so the choice depends on the ids only, not on their order or on which other ids are present.
std::vector<FrameSurvey::Tracked> tracked_particles(const std::vector<Vec3f>& positions,
                                                    const std::vector<Vec3f>& velocities,
                                                    const std::vector<uint32_t>& ids) {
  constexpr size_t kTracked = 64;
  auto mix = [](uint32_t id) {
    uint64_t z = uint64_t(id) + 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  std::vector<std::pair<uint64_t, uint32_t>> keys(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) keys[i] = {mix(ids[i]), uint32_t(i)};
  const size_t n = std::min(kTracked, keys.size());
  std::partial_sort(keys.begin(), keys.begin() + std::ptrdiff_t(n), keys.end());
  std::vector<FrameSurvey::Tracked> tracked(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t i = keys[k].second;
    tracked[k] = {ids[i], positions[i], velocities[i]};
  }
  std::sort(tracked.begin(), tracked.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return tracked;
}

}  // namespace

FrameSurvey survey_positions(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& velocities,
                             const std::vector<uint32_t>& ids) {
  FrameSurvey f;
  f.particles = positions.size();
  // The 4 outermost coordinates per side, kept sorted outermost first (low sides: smallest).
  constexpr size_t kSheetRank = 4;
  std::array<std::array<float, kSheetRank>, 6> outer;
  for (size_t side = 0; side < 6; ++side) outer[side].fill(side % 2 == 0 ? INFINITY : -INFINITY);
  double sum[3] = {0.0, 0.0, 0.0};
  for (const Vec3f& p : positions) {
    f.bounds.extend(p);
    for (int a = 0; a < 3; ++a) sum[a] += double(p[a]);
    for (size_t side = 0; side < 6; ++side) {
      // Sides are compared as "more outward is smaller": negate the high sides.
      const float v = side % 2 == 0 ? p[int(side / 2)] : -p[int(side / 2)];
      auto& o = outer[side];
      const float worst = side % 2 == 0 ? o[kSheetRank - 1] : -o[kSheetRank - 1];
      if (!(v < worst)) continue;
      size_t k = kSheetRank - 1;
      while (k > 0 && v < (side % 2 == 0 ? o[k - 1] : -o[k - 1])) o[k] = o[k - 1], --k;
      o[k] = side % 2 == 0 ? v : -v;
    }
  }
  for (size_t side = 0; side < 6; ++side) {
    const size_t rank = std::min<size_t>(kSheetRank, std::max<size_t>(positions.size(), 1)) - 1;
    f.sheet[side] = positions.empty() ? NAN : outer[side][rank];
  }
  for (int a = 0; a < 3; ++a) f.centroid[a] = positions.empty() ? NAN : float(sum[a] / double(positions.size()));
  if (!velocities.empty()) {
    double v[3] = {0.0, 0.0, 0.0};
    for (const Vec3f& u : velocities)
      for (int a = 0; a < 3; ++a) v[a] += double(u[a]);
    for (int a = 0; a < 3; ++a) f.mean_velocity[a] = float(v[a] / double(velocities.size()));
    const float extent = (f.bounds.max - f.bounds.min).maxCoeff();
    if (extent > 0.0f && std::isfinite(extent)) {
      f.column = std::exp2(std::ceil(std::log2(extent / 8.0f)));
      f.fronts = column_fronts(positions, velocities, f.bounds, f.column);
    }
    if (ids.size() == positions.size()) f.tracked = tracked_particles(positions, velocities, ids);
  }
  return f;
}

float median_spacing(const std::vector<Vec3f>& positions, size_t samples) {
  const size_t n = positions.size();
  if (n < 2) return 0.0f;
  const size_t count = std::min(samples, n), stride = n / count;
  std::vector<float> nearest(count);
  parallel_for(count, 8, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) {
      const size_t i = k * stride;
      float best = INFINITY;
      for (size_t j = 0; j < n; ++j)
        if (j != i) best = std::min(best, (positions[j] - positions[i]).squaredNorm());
      nearest[k] = std::sqrt(best);
    }
  });
  std::nth_element(nearest.begin(), nearest.begin() + count / 2, nearest.end());
  return nearest[count / 2];
}

FluidSurvey survey_fluid_files(const std::string& pattern, const std::vector<int>& frames,
                               const std::filesystem::path& keep, bool quiet, const FluidReadOptions& read) {
  if (frames.empty()) fail(pattern, ": no frames to survey");
  FluidSurvey survey;
  survey.pattern = pattern;
  survey.read = read;
  survey.frames.resize(frames.size());
  // A survey kept under other read options measured other coordinates: it is not this one. The same
  // files typed another way (relative, absolute, $F4 for %04d) are the same survey.
  const std::string kept_as = canonical_frame_pattern(pattern) + (read.up == UpAxis::Y ? "" : str(" (", up_axis_name(read.up), "-up)")) +
                              (read.vdb_grid.empty() ? "" : str(" (grid ", read.vdb_grid, ")"));
  const Kept kept = read_kept(keep, kept_as);
  if (kept.rejected > 0)
    survey.notes.push_back(str(keep.string(), ": ", kept.rejected, kept.rejected > 1 ? " entries" : " entry",
                               " did not match ", kept.rejected > 1 ? "their" : "its",
                               " digest (edited or damaged); surveyed again from the fluid files"));

  std::vector<size_t> todo;
  for (size_t k = 0; k < frames.size(); ++k) {
    const std::string path = expand_frame_pattern(pattern, frames[k]);
    const FileIdentity id = file_identity(path);
    auto it = std::find_if(kept.frames.begin(), kept.frames.end(),
                           [&](const FrameSurvey& f) { return f.frame == frames[k]; });
    if (it != kept.frames.end() && it->file == id) {
      survey.frames[k] = *it;
    } else {
      survey.frames[k].frame = frames[k];
      survey.frames[k].file = id;
      todo.push_back(k);
    }
  }
  // The spacing is measured in the first frame holding two particles or more (a sequence may start empty).
  auto spacing_index = [&] {
    for (size_t k = 0; k < survey.frames.size(); ++k)
      if (survey.frames[k].particles >= 2) return k;
    return size_t(0);
  };
  auto spacing_known = [&](size_t k) { return kept.spacing_frame == frames[k] && kept.spacing_file == survey.frames[k].file; };
  if (todo.empty() && spacing_known(spacing_index())) {
    survey.spacing = kept.spacing;
    return survey;
  }

  // Frames are independent: read them in parallel, each written by its own task.
  Progress progress("survey fluid", todo.size(), quiet || todo.size() < 8);
  progress.note(str("surveying ", todo.size(), " fluid frames (bounds for the domain and camera)"));
  std::vector<std::string> errors(todo.size());
  parallel_for(todo.size(), 1, [&](size_t b, size_t e) {
    for (size_t t = b; t < e; ++t) {
      FrameSurvey& f = survey.frames[todo[t]];
      const std::string path = expand_frame_pattern(pattern, f.frame);
      try {
        const FluidFrame frame = read_fluid_file(path, read);
        const FileIdentity id = f.file;
        f = survey_positions(frame.positions, frame.velocities, frame.ids);
        f.frame = frames[todo[t]];
        f.file = id;
      } catch (const Error& error) {
        errors[t] = str("frame ", f.frame, ": ", error.what());
      }
    }
  });
  for (const std::string& e : errors)
    if (!e.empty()) throw Error(e);
  progress.finish(str(todo.size(), " frames read"));
  const size_t spacing_at = spacing_index();
  if (spacing_known(spacing_at)) {
    survey.spacing = kept.spacing;
  } else {
    const FluidFrame first = read_fluid_file(expand_frame_pattern(pattern, frames[spacing_at]), read);
    survey.spacing = median_spacing(first.positions);
  }

  if (!keep.empty()) {
    Json j = spacing_json(kept_as, survey.spacing, frames[spacing_at], survey.frames[spacing_at].file);
    j["version"] = kSurveyVersion;
    j["frames"] = Json::array();
    // Keep what was known of frames outside this range too, so other ranges stay cheap.
    std::vector<FrameSurvey> all = survey.frames;
    for (const FrameSurvey& f : kept.frames)
      if (!std::binary_search(frames.begin(), frames.end(), f.frame)) all.push_back(f);
    std::sort(all.begin(), all.end(), [](const FrameSurvey& a, const FrameSurvey& b) { return a.frame < b.frame; });
    for (const FrameSurvey& f : all) j["frames"].push_back(to_json(f));
    write_file_atomically(keep, [&](std::ostream& out) { out << j.dump() << '\n'; });
  }
  return survey;
}

}  // namespace spume
