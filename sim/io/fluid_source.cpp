#include "sim/io/fluid_source.h"

#include <algorithm>
#include <unordered_map>

#include "sim/core/error.h"
#include "sim/core/frame_order.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/frame_pattern_hint.h"
#include "sim/io/particle_file.h"

namespace spume {

std::vector<int> missing_frames(const std::vector<int>& frames) {
  std::vector<int> missing;
  for (size_t k = 1; k < frames.size(); ++k)
    for (int f = frames[k - 1] + 1; f < frames[k]; ++f) missing.push_back(f);
  return missing;
}

FluidFrame interpolate_frames(const FluidFrame& a, const FluidFrame& b, int frame, double time) {
  FluidFrame out;
  out.index = frame;
  out.time = time;
  const double span = b.time - a.time;
  const float s = span > 0.0 ? float((time - a.time) / span) : 0.0f;
  const float since_a = float(time - a.time);
  // Particles of a, matched in b by id (by index when neither has ids, the counts agree and the order
  // is kept); particles b does not have move on with their own velocity (or stay), those only b has are
  // left out. Without ids and without a kept order nothing is matched.
  const bool ids = a.has_ids() && b.has_ids();
  const bool by_index = !ids && a.size() == b.size() && index_order_mismatch(a, b, span).empty();
  std::unordered_map<uint32_t, uint32_t> in_b;
  if (ids)
    for (uint32_t j = 0; j < b.size(); ++j) in_b.emplace(b.id(j), j);
  const bool velocities = a.has_velocities() && b.has_velocities();
  for (uint32_t i = 0; i < a.size(); ++i) {
    int64_t j = -1;
    if (by_index) {
      j = i;
    } else if (auto it = in_b.find(a.id(i)); it != in_b.end()) {
      j = it->second;
    }
    if (j >= 0) {
      out.positions.push_back(a.positions[i] + s * (b.positions[size_t(j)] - a.positions[i]));
      if (velocities) out.velocities.push_back(a.velocities[i] + s * (b.velocities[size_t(j)] - a.velocities[i]));
    } else {
      const Vec3f v = a.has_velocities() ? a.velocities[i] : Vec3f::Zero();
      out.positions.push_back(a.positions[i] + since_a * v);
      if (velocities) out.velocities.push_back(v);
    }
    if (a.has_ids()) out.ids.push_back(a.ids[i]);
    if (!a.masses.empty()) out.masses.push_back(a.masses[i]);
  }
  return out;
}

namespace {

class FileSequenceSource final : public FluidSource {
 public:
  FileSequenceSource(std::string pattern, double fps, bool allow_gaps, float velocity_scale, FluidReadOptions read)
      : pattern_(std::move(pattern)), fps_(fps), allow_gaps_(allow_gaps), velocity_scale_(velocity_scale),
        read_(std::move(read)) {
    if (!is_frame_pattern(pattern_))
      fail(pattern_, ": a fluid file pattern needs one frame placeholder (%d, %04d, #### or $F, $F4)");
    files_ = find_pattern_frames(pattern_);
    if (files_.empty()) fail(pattern_, ": no files match this pattern", unmatched_pattern_hint(pattern_));
    frames_ = files_;
    if (allow_gaps_)
      for (int f = files_.front(); f <= files_.back(); ++f) frames_.push_back(f);
    std::sort(frames_.begin(), frames_.end());
    frames_.erase(std::unique(frames_.begin(), frames_.end()), frames_.end());
  }
  std::vector<int> frame_numbers() const override { return frames_; }
  std::vector<int> file_frames() const override { return files_; }
  FluidFrame load(int frame) override {
    if (!std::binary_search(files_.begin(), files_.end(), frame)) {
      if (!allow_gaps_ || frame < files_.front() || frame > files_.back())
        fail(expand_frame_pattern(pattern_, frame), ": no such fluid frame");
      // A gap: the frames on either side, interpolated at this frame's time.
      const auto after = std::upper_bound(files_.begin(), files_.end(), frame);
      return interpolate_frames(read(*(after - 1)), read(*after), frame, double(frame) / fps_);
    }
    return read(frame);
  }
  std::string describe() const override {
    return str(pattern_, " (", files_.size(), " frames, ", files_.front(), "-", files_.back(), ")");
  }

 private:
  FluidFrame read(int frame) const {
    const std::string path = expand_frame_pattern(pattern_, frame);
    FluidFrame f = read_fluid_file(path, read_);
    if (f.size() == 0) fail(path, ": holds no fluid particles; every fluid frame needs at least one");
    f.index = frame;
    f.time = double(frame) / fps_;
    if (velocity_scale_ != 1.0f)
      for (Vec3f& v : f.velocities) v *= velocity_scale_;
    return f;
  }

  std::string pattern_;
  double fps_;
  bool allow_gaps_;
  float velocity_scale_;
  FluidReadOptions read_;
  std::vector<int> files_, frames_;
};

}  // namespace

std::unique_ptr<FluidSource> make_file_source(const std::string& pattern, double fps, bool allow_gaps,
                                              float velocity_scale, const FluidReadOptions& read) {
  return std::make_unique<FileSequenceSource>(pattern, fps, allow_gaps, velocity_scale, read);
}

}  // namespace spume
