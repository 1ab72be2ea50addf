#include "fluid_source.h"

#include "core/error.h"
#include "io/frame_pattern.h"
#include "io/particle_file.h"

namespace spume {
namespace {

class FileSequenceSource final : public FluidSource {
 public:
  FileSequenceSource(std::string pattern, double fps) : pattern_(std::move(pattern)), fps_(fps) {
    if (!is_frame_pattern(pattern_))
      fail(pattern_, ": a fluid file pattern needs one frame placeholder (%d, %04d or ####)");
    frames_ = find_pattern_frames(pattern_);
    if (frames_.empty()) fail(pattern_, ": no files match this pattern");
  }
  std::vector<int> frame_numbers() const override { return frames_; }
  FluidFrame load(int frame) override {
    const std::string path = expand_frame_pattern(pattern_, frame);
    FluidFrame f = read_fluid_file(path);
    if (f.size() == 0) fail(path, ": holds no fluid particles; every fluid frame needs at least one");
    f.index = frame;
    f.time = double(frame) / fps_;
    return f;
  }
  std::string describe() const override {
    return str(pattern_, " (", frames_.size(), " frames, ", frames_.front(), "-", frames_.back(), ")");
  }

 private:
  std::string pattern_;
  double fps_;
  std::vector<int> frames_;
};

}  // namespace

std::unique_ptr<FluidSource> make_file_source(const std::string& pattern, double fps) {
  return std::make_unique<FileSequenceSource>(pattern, fps);
}

}  // namespace spume
