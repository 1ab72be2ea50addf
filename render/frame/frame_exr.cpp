#include "render/frame/frame_exr.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "render/image/exr_io.h"
#include "sim/core/error.h"
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

std::string describe_frame_exr(const std::filesystem::path& path) {
  const ExrContents c = read_exr(path);
  const size_t n = size_t(c.width) * size_t(c.height);
  std::ostringstream out;
  out << path.string() << "\n  format: OpenEXR, " << c.width << "x" << c.height << ", " << c.compression << ", "
      << c.channels.size() << " channels\n";
  // Layers by the channel names' prefixes, in the file's (alphabetical) order.
  std::map<std::string, std::vector<std::string>> layers;
  for (const auto& [name, values] : c.channels) {
    const size_t dot = name.rfind('.');
    layers[dot == std::string::npos ? "" : name.substr(0, dot)].push_back(
        (dot == std::string::npos ? name : name.substr(dot + 1)) + (c.full_float.at(name) ? " (float)" : ""));
  }
  for (const auto& [layer, names] : layers) {
    out << "  " << (layer.empty() ? "beauty and depth" : layer) << ":";
    for (const std::string& name : names) out << " " << name;
    const auto alpha = c.channels.find(layer.empty() ? "A" : layer + ".A");
    if (alpha != c.channels.end() && !layer.empty()) {
      const size_t covered = size_t(std::count_if(alpha->second.begin(), alpha->second.end(), [](float a) { return a > 0.0f; }));
      out << str("; covers ", std::lround(100.0 * double(covered) / double(n)), "% of the pixels");
    }
    if (layer == "forward") {
      double largest = 0.0;
      const std::vector<float>&u = c.channels.at("forward.u"), &v = c.channels.at("forward.v");
      for (size_t p = 0; p < n; ++p) largest = std::max(largest, std::hypot(double(u[p]), double(v[p])));
      out << str("; largest ", largest, " pixels a frame");
    }
    out << "\n";
  }
  if (const auto z = c.channels.find("Z"); z != c.channels.end()) {
    float lo = INFINITY, hi = -INFINITY;
    for (float d : z->second)
      if (d < FrameLayers::kSkyDistance) lo = std::min(lo, d), hi = std::max(hi, d);
    if (lo <= hi) out << "  Z: " << lo << " .. " << hi << " m (sky at " << FrameLayers::kSkyDistance << ")\n";
  }
  for (const char* key : {"spume/version", "spume/scene", "spume/keysDigest"})
    if (const auto s = c.strings.find(key); s != c.strings.end()) out << "  " << key << ": " << s->second << "\n";
  if (const auto s = c.strings.find("comments"); s != c.strings.end()) out << "  comments: " << s->second << "\n";
  if (c.strings.find(kRecord) == c.strings.end()) out << "  (not a spume frame: no spume/record)\n";
  return out.str();
}

std::optional<std::string> read_frame_exr_record(const std::filesystem::path& path) {
  return read_exr_string(path, kRecord);
}

}  // namespace spume
