#include "render/frame/frame_exr.h"

#include <nlohmann/json.hpp>

#include "render/image/exr_io.h"
#include "sim/io/stage_record.h"

namespace spume {
namespace {

constexpr const char* kRecord = "spume/record";

void add_rgba(std::vector<ExrChannel>& channels, const std::string& prefix, const std::vector<Rgba>& pixels) {
  static const char* const kNames[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) channels.push_back({prefix + kNames[c], pixels.data()->data() + c, 4});
}

}  // namespace

const char* spume_version() { return SPUME_VERSION; }

void write_frame_exr(const std::filesystem::path& path, const FrameLayers& frame, const FrameProvenance& provenance) {
  std::vector<ExrChannel> channels;
  add_rgba(channels, "", frame.beauty);
  channels.push_back({"Z", frame.distance.data(), 1, true});
  std::string order;
  for (const RgbaLayer& l : frame.layers) add_rgba(channels, l.name + ".", l.pixels);
  if (!frame.motion.empty()) {
    static const char* const kMotion[4] = {"forward.u", "forward.v", "backward.u", "backward.v"};
    for (int c = 0; c < 4; ++c) channels.push_back({kMotion[c], frame.motion.data()->data() + c, 4});
  }
  for (size_t i = 3; i < frame.layers.size(); ++i) order += (i > 3 ? " + " : "") + frame.layers[i].name;
  order = (order.empty() ? "" : "(" + order + ") over ") + "water over opaque over sky";
  const ExrStrings strings = {
      {"comments", "spume " + std::string(spume_version()) + ", linear RGB, premultiplied. Beauty (R,G,B,A) = " + order +
                       ". Z: m from the camera to the first surface. forward.u/v, backward.u/v: pixels per frame, v up."},
      {kRecord, provenance.record},
      {"spume/keysDigest", record_digest(nlohmann::json::parse(provenance.record))},
      {"spume/scene", provenance.scene},
      {"spume/version", spume_version()}};
  write_exr(path, frame.width, frame.height, channels, strings);
}

std::optional<std::string> read_frame_exr_record(const std::filesystem::path& path) {
  return read_exr_string(path, kRecord);
}

}  // namespace spume
